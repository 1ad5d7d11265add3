"""A material at one hit, ready for the BSDF functions: its closure rows, their spectral parameters at
the path's wavelengths, and the glass index (at the hero wavelength when the glass disperses).

Spectral sources (``bsdf.closure``) are spectrum-table ids, 1, or colours a program computed at this hit
(``spectra.rgb_lut``: reflectances for albedos and tints of F0, unbounded spectra for closure weights).
Materials whose weights vary get selection weights per hit (``selection_weights``): the tint's mean
times an estimate of the closure's albedo seen from ``wo``.
"""

from __future__ import annotations

from ..bsdf.closure import (C_GLASS, C_KIND, C_S1, C_SPECTRUM, C_TINT, C_TINT_SCALE, C_WEIGHT, CONDUCTOR, DIELECTRIC,
                            DIFFUSE, HAIR, TRANSLUCENT)
from ..bsdf.closure_frame import view_cosine
from ..bsdf.conductor import mean_tinted_reflectance
from ..jit import inlined, kernel
from ..spectra.dispersion import refractive_index
from ..spectra.rgb_lut import reflectance_values, unbounded_values
from ..spectra.table import spectrum_values


@inlined
def copy_rows(materials, material, rows):
    """Copy ``material``'s closure rows into ``rows``; returns their count."""
    start = materials.closure_start[material]
    count = materials.closure_count[material]
    for c in range(count):
        row = materials.closures[start + c]
        for j in range(row.shape[0]):
            rows[c, j] = row[j]
    return count


@kernel
def _fill(materials, spectra, source, wavelength_nm, regs, bounded, out):
    if source >= 0.0:
        spectrum_values(spectra, int(source), wavelength_nm, out)
    elif source > -1.5:
        for k in range(out.shape[0]):
            out[k] = 1.0
    else:
        r = int(-2.0 - source)
        if bounded:
            reflectance_values(materials.lut, regs[r], regs[r + 1], regs[r + 2], wavelength_nm, out)
        else:
            unbounded_values(materials.lut, regs[r], regs[r + 1], regs[r + 2], wavelength_nm, out)


@inlined
def resolve_spectral(materials, spectra, count, wavelength_nm, hero, rows, spectral, eta, glass_clamps, regs):
    """Fill ``spectral[c]`` (float64 [3, K]) and ``eta[c]`` for the ``count`` closures in ``rows``."""
    for c in range(count):
        row = rows[c]
        _fill(materials, spectra, row[C_SPECTRUM], wavelength_nm, regs, True, spectral[c, 0])
        # a fibre's absorption coefficient (``HAIR``, ``C_S1``) is not bounded by 1
        _fill(materials, spectra, row[C_S1], wavelength_nm, regs, int(row[C_KIND]) != HAIR, spectral[c, 1])
        _fill(materials, spectra, row[C_TINT], wavelength_nm, regs, False, spectral[c, 2])
        scale = row[C_TINT_SCALE]
        if scale != 1.0:
            for k in range(spectral.shape[2]):
                spectral[c, 2, k] *= scale
        eta[c] = 1.0
        if int(row[C_KIND]) == DIELECTRIC:
            glass = int(row[C_GLASS])
            index, clamped = refractive_index(materials.glasses[glass], wavelength_nm[hero])
            if clamped:
                glass_clamps[glass] += 1
            eta[c] = index


@inlined
def resolve_material(materials, spectra, material, wavelength_nm, hero, rows, spectral, eta, glass_clamps):
    """Rows and spectral parameters of a material whose closures do not vary (no program); returns the
    closure count."""
    count = copy_rows(materials, material, rows)
    resolve_spectral(materials, spectra, count, wavelength_nm, hero, rows, spectral, eta, glass_clamps,
                     materials.programs.constants)
    return count


@kernel
def selection_weights(rows, spectral, count, wavelength_nm, cos_o):
    """Per-hit sampling weights: the closure's mean tint times its estimated albedo at ``cos_o``."""
    k_count = spectral.shape[2]
    for c in range(count):
        kind = int(rows[c, C_KIND])
        if kind == CONDUCTOR:
            share = mean_tinted_reflectance(rows[c], spectral[c], view_cosine(rows[c], cos_o), wavelength_nm)
        else:
            total = 0.0
            for k in range(k_count):
                total += spectral[c, 2, k] * (spectral[c, 0, k] if kind == DIFFUSE or kind == TRANSLUCENT else 1.0)
            share = total / k_count
        rows[c, C_WEIGHT] = max(share, 0.0)
