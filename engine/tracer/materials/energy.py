"""Blender's Multiscatter GGX at a hit: the tint of every compensated closure (``C_MULTISCATTER``) scaled by
the energy its single scattering misses (``bsdf.multiscatter``), per wavelength.

Cycles computes the same factor when it sets a closure up (``microfacet_ggx_preserve_energy``): it depends
on the view direction and the closure's parameters, not on the light direction, so scaling the tint once
per hit scales evaluate and sample weights alike and leaves every pdf as it is. Mirrors (alpha below
``SMOOTH_ALPHA``) lose nothing and are left alone.
"""

from __future__ import annotations

import math

from ..bsdf.closure import C_ALPHA, C_KIND, C_MS_COLOUR, C_MULTISCATTER, DIELECTRIC, SMOOTH_ALPHA
from ..bsdf.closure_frame import view_cosine
from ..bsdf.multiscatter import energy_scale, glass_albedo, model_fss, reflection_albedo
from ..jit import inlined
from ..spectra.rgb_lut import bounded_coefficients
from ..spectra.table import sigmoid_polynomial, spectrum_value


@inlined
def _colour_at(materials, spectra, source, regs, wavelength_nm):
    """Value at ``wavelength_nm`` of a bounded (reflectance) spectral source (see ``bsdf.closure``)."""
    if source >= 0.0:
        return spectrum_value(spectra, int(source), wavelength_nm)
    if source > -1.5:
        return 1.0
    r = int(-2.0 - source)
    red, green, blue = regs[r], regs[r + 1], regs[r + 2]
    red = min(max(red, 0.0), 1.0) if math.isfinite(red) else 0.0
    green = min(max(green, 0.0), 1.0) if math.isfinite(green) else 0.0
    blue = min(max(blue, 0.0), 1.0) if math.isfinite(blue) else 0.0
    if red == green and green == blue:
        return red
    c0, c1, c2, scale = bounded_coefficients(materials.lut, red, green, blue)
    return scale * sigmoid_polynomial(c0, c1, c2, wavelength_nm)


@inlined
def compensate_energy(materials, spectra, tables, rows, spectral, eta, count, cos_o, backfacing, wavelength_nm, regs):
    """Scale ``spectral[c, 2]`` (the tint) of the compensated closures among ``count`` resolved ones, seen at
    view cosine ``cos_o`` (``backfacing``: from inside, where a glass's index is 1/η). ``tables`` is a
    ``bsdf.multiscatter.EnergyTables``; ``regs`` the registers the closures' sources were resolved from."""
    for c in range(count):
        row = rows[c]
        alpha = row[C_ALPHA]
        if not row[C_MULTISCATTER] > 0.0 or not alpha >= SMOOTH_ALPHA:
            continue
        mu = min(abs(view_cosine(row, cos_o)), 1.0)
        rough = math.sqrt(min(alpha, 1.0))
        if int(row[C_KIND]) == DIELECTRIC:
            index = 1.0 / eta[c] if backfacing else eta[c]
            e, e_avg = glass_albedo(tables, rough, mu, index)
        else:
            e, e_avg = reflection_albedo(tables, rough, mu)
        if not (e > 0.0 and e < 1.0):
            continue
        source = row[C_MS_COLOUR]
        for k in range(spectral.shape[2]):
            fss = -1.0 if int(row[C_KIND]) == DIELECTRIC else model_fss(tables, row, spectral[c], k)
            if fss < 0.0:
                fss = _colour_at(materials, spectra, source, regs, wavelength_nm[k])
            spectral[c, 2, k] *= energy_scale(fss, e, e_avg)
