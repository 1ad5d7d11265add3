"""Scene data to per-wavelength evaluators, using the physics modules.

Everything here returns callables ``f(wavelength_nm [n,K]) -> [n,K]`` (or the
wavelength-mode helper), so the integrator never deals with RGB: reflectances
are upsampled from RGB (sigmoid-polynomial, ``rgb_to_spectrum``), emitters use
``emission_spectrum`` (luminance-normalised), glasses their catalogue
dispersion, metals their measured n, k.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .scene import SpectrumSpec


class PathWavelengths(np.ndarray):
    """Wavelengths [n,K] (nm) of a chunk of paths that remember which paths they are.

    A path keeps its wavelengths for life, so every spectrum (albedo, emitter) is
    evaluated once per chunk and then looked up at each bounce: indexing rows
    (``lam[mask]``, ``lam[indices]``, ``np.compress(mask, lam, axis=0)``) keeps the link; anything else gives a plain array.
    """

    def __new__(cls, wavelength_nm):
        full = np.ascontiguousarray(wavelength_nm, dtype=np.float64)
        obj = full.view(cls)
        obj._rows = np.arange(len(full))
        obj._cache = {}
        obj._full = full
        return obj

    def __array_finalize__(self, obj):
        self._rows = None
        self._cache = None
        self._full = None

    def _linked(self, out, linked, rows):
        """``out`` keeps the link to the chunk's cache when it holds whole rows."""
        if self._rows is None or not linked or out.ndim != 2:
            return out.view(np.ndarray)
        out._rows, out._cache, out._full = rows(), self._cache, self._full
        return out

    def whole_chunk(self) -> "PathWavelengths":
        """All of the chunk's paths, in order, sharing this array's spectrum cache."""
        out = self._full.view(PathWavelengths)
        out._rows, out._cache, out._full = np.arange(len(self._full)), self._cache, self._full
        return out

    def take(self, indices, axis=None, out=None, mode="raise"):
        result = super().take(indices, axis=axis, out=out, mode=mode)
        linked = axis == 0 and out is None and np.ndim(indices) == 1
        return self._linked(result, linked, lambda: self._rows.take(indices))

    def compress(self, condition, axis=None, out=None):
        result = super().compress(condition, axis=axis, out=out)
        return self._linked(result, axis == 0 and out is None, lambda: self._rows.compress(condition))

    def __getitem__(self, key):
        result = super().__getitem__(key)
        if not isinstance(result, np.ndarray):
            return result
        linked = isinstance(key, slice) or (isinstance(key, np.ndarray) and key.ndim == 1)
        return self._linked(result, linked, lambda: self._rows[key])


def cached(key, fn, lam) -> np.ndarray:
    """``fn(lam)`` [n,K], computed once per chunk when ``lam`` is a ``PathWavelengths``."""
    rows = getattr(lam, "_rows", None)
    if rows is None:
        return np.asarray(fn(np.asarray(lam)), dtype=np.float64)
    table = lam._cache.get(key)
    if table is None:
        table = lam._cache[key] = np.asarray(fn(lam._full), dtype=np.float64)
    return np.take(table, rows, axis=0)


class GuidedVisibleWavelengths:
    """``cie``-mode wavelength sampling guided by the scene's monochromatic lines.

    Density: half the visible-light distribution of ``wavelengths.py``, half the
    emission lines (shared equally), tabulated on 0.1 nm cells (piecewise constant,
    so sampled wavelengths and their pdf agree exactly). As in the hero scheme, the
    K columns are inverse-CDF images of rotated copies of one uniform number, so
    each column has this marginal density. Without it a 10 nm line would be found
    by only ~1/50 of the wavelengths drawn.
    """

    CELL_NM = 0.1

    def __init__(self, lines, line_fraction=0.5):
        from .spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM, visible_wavelength_pdf

        cells = int(round((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / self.CELL_NM))
        self.edges = np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, cells + 1)
        centres = 0.5 * (self.edges[1:] + self.edges[:-1])
        density = (1.0 - line_fraction) * visible_wavelength_pdf(centres)
        for line in lines:
            shape = np.asarray(line.evaluate(centres), dtype=np.float64)
            density += line_fraction / len(lines) * shape / (shape.sum() * self.CELL_NM)
        self.mass = density * self.CELL_NM / (density.sum() * self.CELL_NM)
        self.cdf = np.concatenate([[0.0], np.cumsum(self.mass)])
        self.cdf[-1] = 1.0

    def sample(self, u, count):
        """(wavelength_nm [N, count], pdf [N, count]) from uniform ``u`` [N]."""
        rotated = np.mod(np.asarray(u, dtype=np.float64)[:, None] + np.arange(count) / count, 1.0)
        cell = np.clip(np.searchsorted(self.cdf, rotated, side="right") - 1, 0, len(self.mass) - 1)
        frac = np.clip((rotated - self.cdf[cell]) / self.mass[cell], 0.0, 1.0)
        wavelength_nm = self.edges[cell] + frac * self.CELL_NM
        return wavelength_nm, self.mass[cell] / self.CELL_NM


class WavelengthMode:
    """Sampling of the wavelengths a path carries and conversion of its radiance to RGB.

    ``lines``: emission spectra of monochromatic emitters; in ``cie`` mode wavelength
    sampling is then guided towards them (``GuidedVisibleWavelengths``)."""

    def __init__(self, settings, lines=()):
        self.mode = settings.wavelength_mode
        self.guided = None
        if self.mode == "cie":
            self.count = int(settings.wavelengths_per_path)
            self.channels = None
            if lines:
                self.guided = GuidedVisibleWavelengths(list(lines))
        else:
            from .spectra.wavelengths import GaussianChannels

            self.count = 3
            self.channels = GaussianChannels(settings.channel_means_nm, settings.channel_sigmas_nm)

    @property
    def dimensions(self) -> int:
        """Uniform numbers one path needs to draw its wavelengths."""
        return 1 if self.mode == "cie" else 3

    def sample(self, u: np.ndarray):
        """``u`` [n, dimensions] -> (wavelength_nm [n,K], pdf [n,K])."""
        if self.mode == "cie":
            if self.guided is not None:
                return self.guided.sample(u[:, 0], self.count)
            from .spectra.wavelengths import sample_visible_wavelengths

            return sample_visible_wavelengths(u[:, 0], self.count)
        return self.channels.sample(u)

    def to_rgb(self, radiance, wavelength_nm, pdf) -> np.ndarray:
        """Per-path spectral radiance [n,K] to scene-linear Rec.709 [n,3]."""
        from .spectra import cie

        if self.mode == "cie":
            from .sampling import transform_rows

            # cie.xyz_to_linear_rec709 without its BLAS matmul (see sampling.dot_vector)
            return transform_rows(cie.spectral_samples_to_xyz(radiance, wavelength_nm, pdf), cie.XYZ_TO_LINEAR_REC709)
        return cie.gaussian_channel_samples_to_rgb(radiance, wavelength_nm, pdf, self.channels)


class _Constant:
    def __init__(self, value):
        self.value = float(value)

    def __call__(self, lam):
        return np.full(np.shape(lam), self.value)


class _Reflectance:
    def __init__(self, rgb):
        from .spectra.rgb_to_spectrum import reflectance_coefficients

        self.coefficients = reflectance_coefficients(np.asarray(rgb, dtype=np.float64))

    def __call__(self, lam):
        return cached(self, self._evaluate, lam)

    def _evaluate(self, lam):
        from .spectra.rgb_to_spectrum import evaluate_sigmoid_polynomial

        return evaluate_sigmoid_polynomial(self.coefficients, lam)


def monochromatic_lines(scene, used_materials) -> list:
    """Emission spectra of the scene's monochromatic emitters (lights and used materials)."""
    specs = [light.spectrum for light in scene.lights if light.spectrum.kind == "monochromatic"]
    for m in used_materials:
        mat = scene.materials[m]
        if mat.emission_strength > 0 and mat.emission is not None and mat.emission.kind == "monochromatic":
            specs.append(mat.emission)
    return [emission(spec).spectrum for spec in dict.fromkeys(specs)]


def reflectance(rgb) -> callable:
    """Reflectance spectrum (values in [0,1]) upsampled from a linear Rec.709 albedo."""
    rgb = tuple(float(c) for c in rgb)
    if rgb[0] == rgb[1] == rgb[2] and rgb[0] in (0.0, 1.0):
        return _Constant(rgb[0])  # the sigmoid only approaches 0 and 1
    return _cached_reflectance(rgb)


@lru_cache(maxsize=256)
def _cached_reflectance(rgb):
    return _Reflectance(rgb)


class _Emission:
    def __init__(self, spec: SpectrumSpec):
        from .spectra.emission_spectrum import emission_spectrum

        self.spectrum = emission_spectrum(spec)

    def __call__(self, lam):
        return cached(self, self.spectrum.evaluate, lam)


@lru_cache(maxsize=256)
def emission(spec: SpectrumSpec) -> callable:
    """Luminance-normalised emission spectrum of an emitter (radiance per unit strength)."""
    return _Emission(spec)


def world_emission(color) -> callable:
    """Background radiance spectrum per unit strength for a linear Rec.709 colour."""
    return emission(SpectrumSpec(kind="rgb", rgb=tuple(float(c) for c in color)))


def glass_of(material):
    """The material's ``Glass`` (catalogue name, n_d/V_d, or constant ``ior``)."""
    from .spectra import glass

    if material.glass:
        return glass.glass_by_name(material.glass)
    if material.glass_nd is not None and material.glass_vd is not None:
        return glass.glass_from_abbe(material.glass_nd, material.glass_vd)
    if material.glass_nd is not None:
        return glass.constant_ior(material.glass_nd)
    return glass.constant_ior(material.ior)


def conductor_nk(name: str, lam: np.ndarray):
    """Complex index parts (n [n,K], k [n,K]) of a named metal (cached per chunk)."""
    from .spectra.conductors import conductor_nk as nk

    nk_stack = cached(("nk", name), lambda wl: np.stack(nk(name, wl), axis=-1), lam)
    return nk_stack[..., 0], nk_stack[..., 1]
