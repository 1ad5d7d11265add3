"""A material at one hit, ready for the BSDF functions: its closure rows, their spectral parameters at
the path's wavelengths, and the glass index (at the hero wavelength when the glass disperses).

This is where surface-varying parameters will be evaluated (textures, node programs: issue 12); the
BSDF functions only ever see resolved values.
"""

from __future__ import annotations

from ..bsdf.closure import C_GLASS, C_K, C_KIND, C_N, C_SPECTRUM, CONDUCTOR, DIELECTRIC, DIFFUSE
from ..jit import inlined
from ..spectra.dispersion import refractive_index
from ..spectra.table import spectrum_values


@inlined
def resolve_material(materials, spectra, material, wavelength_nm, hero, rows, spectral, eta, glass_clamps):
    """Fill ``rows[c]``, ``spectral[c]`` (float64 [2, K]) and ``eta[c]`` for each closure of ``material``;
    returns the closure count. ``glass_clamps[g]`` counts indices evaluated outside glass g's range."""
    start = materials.closure_start[material]
    count = materials.closure_count[material]
    for c in range(count):
        row = materials.closures[start + c]
        for j in range(row.shape[0]):
            rows[c, j] = row[j]
        kind = int(row[C_KIND])
        eta[c] = 1.0
        if kind == DIFFUSE:
            spectrum_values(spectra, int(row[C_SPECTRUM]), wavelength_nm, spectral[c, 0])
        elif kind == CONDUCTOR:
            if row[C_N] >= 0.0:
                spectrum_values(spectra, int(row[C_N]), wavelength_nm, spectral[c, 0])
                spectrum_values(spectra, int(row[C_K]), wavelength_nm, spectral[c, 1])
            else:
                spectrum_values(spectra, int(row[C_SPECTRUM]), wavelength_nm, spectral[c, 0])
        elif kind == DIELECTRIC:
            glass = int(row[C_GLASS])
            index, clamped = refractive_index(materials.glasses[glass], wavelength_nm[hero])
            if clamped:
                glass_clamps[glass] += 1
            eta[c] = index
    return count
