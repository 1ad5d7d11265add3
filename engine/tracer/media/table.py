"""The media of a render as the kernels read them (``MediaArrays``), built with the material table.

Every coefficient is a tabulated spectrum of the render's ``SpectrumTable`` on its 1 nm grid, per metre:
``scattering`` σ_s and ``absorption`` σ_a (spectrum ids [M]); ``emission`` (spectrum id [M], -1: none)
with ``emission_strength`` [M] (radiance per metre per unit strength, as surfaces' Emission Strength);
``anisotropy`` [M] (Henyey-Greenstein g); ``grid`` [M] (-1: homogeneous, else the row of ``grids``, a
``density_grid.GridArrays``, whose density scales σ_s and σ_a: the one flag the kernels branch on). The
emission is the sum of the medium's emission terms (``spec.MediumSpec``) tabulated as one spectrum, of
strength 1.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..errors import PrismInputError
from .density_grid import build_grids, check_grid
from ..spectra.wavelengths import VISIBLE_MIN_NM, VISIBLE_NM_GRID

MediaArrays = namedtuple("MediaArrays", "scattering absorption emission emission_strength anisotropy grid grids")

#: g is kept inside (-1, 1): at |g| = 1 the phase function is a delta and its density infinite.
MAX_ANISOTROPY = 0.999


def reflectance_on_grid(rgb) -> np.ndarray:
    """The reflectance spectrum Prism upsamples from linear Rec.709 ``rgb`` (values clamped to 0-1), on
    the 1 nm grid of ``spectra.wavelengths.VISIBLE_NM_GRID``: the spectrum surfaces of that colour reflect."""
    from ..spectra.rgb_to_spectrum import reflectance_coefficients

    rgb = np.clip(np.asarray(rgb, dtype=np.float64), 0.0, 1.0)
    if rgb[0] == rgb[1] == rgb[2] and rgb[0] in (0.0, 1.0):
        return np.full(len(VISIBLE_NM_GRID), float(rgb[0]))
    c0, c1, c2 = reflectance_coefficients(rgb)
    lam = np.asarray(VISIBLE_NM_GRID, dtype=np.float64)
    u = np.clip((c0 * lam + c1) * lam + c2, -1e10, 1e10)
    return 0.5 + 0.5 * u / np.sqrt(1.0 + u * u)


def coefficient_spectra(spec):
    """(σ_s, σ_a) per metre on the 1 nm grid for a ``MediumSpec``."""
    sigma_s = np.zeros(len(VISIBLE_NM_GRID))
    sigma_a = np.zeros(len(VISIBLE_NM_GRID))
    for density, rgb in spec.scatter:
        # Cycles scales σ_s by the colour as given: a colour above 1 scatters more (its shape is upsampled).
        scale = max(max(float(c) for c in rgb), 1.0)
        sigma_s += max(float(density), 0.0) * scale * reflectance_on_grid(np.asarray(rgb, float) / scale)
    for density, *colours in spec.absorb:
        term = np.full(len(VISIBLE_NM_GRID), max(float(density), 0.0))
        for rgb in colours:
            term *= 1.0 - reflectance_on_grid(rgb)
        sigma_a += term
    return sigma_s, sigma_a


def emission_on_grid(spec):
    """Emitted radiance per metre on the 1 nm grid for a ``MediumSpec`` (zeros if it emits nothing)."""
    from ..spectra.emission_spectrum import BlackbodyEmissionSpectrum, RGBEmissionSpectrum

    lam = np.asarray(VISIBLE_NM_GRID, dtype=np.float64)
    total = np.zeros(len(lam))
    for strength, rgb, temperature_k in spec.emission:
        rgb = np.maximum(np.asarray(rgb, dtype=np.float64), 0.0)
        if not (strength > 0.0 and rgb.max() > 0.0):
            continue
        if temperature_k is None:
            scale = float(rgb.max())
            total += strength * scale * np.asarray(RGBEmissionSpectrum(tuple(rgb / scale)).evaluate(lam))
        else:  # the tint filters the blackbody as a reflectance of its colour would
            scale = max(float(rgb.max()), 1.0)
            total += (strength * scale * reflectance_on_grid(rgb / scale)
                      * np.asarray(BlackbodyEmissionSpectrum(temperature_k).evaluate(lam)))
    return total


def _check(spec):
    values = [d for d, *_ in spec.scatter + spec.absorb] + [s for s, *_ in spec.emission] + [spec.anisotropy]
    colours = [c for _, *cs in spec.scatter + spec.absorb for c in cs] + [rgb for _, rgb, _ in spec.emission]
    if not all(np.isfinite(values)) or not all(np.all(np.isfinite(c)) for c in colours):
        raise PrismInputError(f"Material '{spec.name}': a volume setting is NaN or infinite; set it again.")
    grid = getattr(spec, "density_grid", None)
    if grid is not None:
        check_grid(grid, spec.name)
        if any(strength > 0.0 for strength, *_ in spec.emission):
            raise PrismInputError(f"Volume '{spec.name}': a medium driven by a density grid cannot emit in Prism "
                                  "yet; leave its emission out.")


def build_media(materials, used, spectra, outside=None, origin=None):
    """(medium index int32 [len(materials)] (-1: none), ``MediaArrays``, the row of ``outside`` or -1) for the
    ``scene.Material`` list, whose indices in ``used`` get a medium, and ``outside`` (a ``MediumSpec``: the
    World's Volume, the medium everywhere outside meshes that hold one; None: vacuum). ``spectra``: the
    render's ``SpectrumTable``; ``origin`` (m) the point the kernels' positions are relative to (grids)."""
    index = np.full(len(materials), -1, np.int32)
    scattering, absorption, emission, strength, anisotropy, grid, grids = [], [], [], [], [], [], []
    specs = [(m, getattr(material, "medium", None)) for m, material in enumerate(materials) if m in used]
    for m, spec in specs + [(-1, outside)]:
        if spec is None:
            continue
        _check(spec)
        sigma_s, sigma_a = coefficient_spectra(spec)
        if m >= 0:
            index[m] = len(scattering)
        key = ("medium", m, spec.name)
        scattering.append(spectra.tabulated(key + ("sigma_s",), float(VISIBLE_MIN_NM), 1.0, sigma_s))
        absorption.append(spectra.tabulated(key + ("sigma_a",), float(VISIBLE_MIN_NM), 1.0, sigma_a))
        anisotropy.append(float(np.clip(spec.anisotropy, -MAX_ANISOTROPY, MAX_ANISOTROPY)))
        density_grid = getattr(spec, "density_grid", None)
        grid.append(len(grids) if density_grid is not None else -1)
        if density_grid is not None:
            grids.append(density_grid)
        emitted = emission_on_grid(spec)
        if emitted.max() > 0.0:
            emission.append(spectra.tabulated(key + ("emission",), float(VISIBLE_MIN_NM), 1.0, emitted))
            strength.append(1.0)
        else:
            emission.append(-1)
            strength.append(0.0)
    arrays = MediaArrays(np.array(scattering or [0], np.int32), np.array(absorption or [0], np.int32),
                         np.array(emission or [-1], np.int32), np.array(strength or [0.0]),
                         np.array(anisotropy or [0.0]), np.array(grid or [-1], np.int32),
                         build_grids(grids, origin))
    return index, arrays, (len(scattering) - 1 if outside is not None else -1)
