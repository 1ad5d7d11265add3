"""The emission a grid medium's walk gathers at its tentative collisions (``delta_tracking``).

Along a segment the emitted light is ∫ T(s) ε(x_s) ds. Delta tracking draws tentative collisions at the
majorant's rate μ, and every one of them before the real collision is a point where the path could take
the emission: with n null collisions before it, its contribution per wavelength k is the prefix's f_k
times T_maj,k over the gap times ε_k, and its probability for the tracker of wavelength j the prefix's p_j
times T_maj,j μ_j over the gap; weighted by f_k / ((1/K) Σ_j p_j), as every event of the walk, the sum over
tentative collisions estimates the integral (the track-length estimator of pbrt-v4's volumetric path
tracer, Pharr et al. 2023 §14.2, with Miller et al. 2019's spectral MIS). Blender's emission does not scale
with density, so an emitting grid medium's majorant carries ``MediaArrays.emission_rate`` on top of
D_max σ_t: a null rate that adds tentative collisions (with σ_n = μ - D σ_t they change no expectation)
where the smoke is thin or absent and the fire still glows.

ε at a point is the medium's emission spectrum, or, where the temperature grid varies it, the rows of
``temperature_emission`` interpolated linearly in the grid's value.
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..spectra.table import spectrum_value


@inlined
def emission_at(media, spectra, medium, value, wavelength_nm):
    """Emitted radiance per metre of ``medium`` at ``wavelength_nm`` where its emission grid reads ``value``
    (any value for a medium without one)."""
    first = media.emission[medium]
    rows = media.emission_rows[medium]
    if rows == 1:
        return spectrum_value(spectra, first, wavelength_nm)
    x = max(value, 0.0) / media.emission_step[medium]
    row = min(int(x), rows - 2)
    w = min(x - row, 1.0)
    return ((1.0 - w) * spectrum_value(spectra, first + row, wavelength_nm)
            + w * spectrum_value(spectra, first + row + 1, wavelength_nm))


@inlined
def gather_emission(state, i, media, spectra, value, walk, f, p, sigma_t, gap):
    """Add to path ``i``'s radiance the emission at a tentative collision reached after ``gap`` (m), before
    its event multiplies ``f`` and ``p`` (the walk's prefix, ``delta_tracking``); ``value``: the emission
    grid's value there. ``walk``: (medium, channel, collapsed, scale_t, extra): μ_k = scale_t σ_t,k + extra."""
    medium, channel, collapsed, scale_t, extra = walk
    lam = state.wavelength[i]
    k_used = lam.shape[0]
    mu_c = scale_t * sigma_t[channel] + extra
    mixture = 0.0
    for k in range(k_used):
        if collapsed and k != channel:
            continue
        mu_k = scale_t * sigma_t[k] + extra
        mixture += p[k] * math.exp(-(mu_k - mu_c) * gap) * mu_k
    if not collapsed:
        mixture /= k_used
    if not mixture > 0.0:
        return
    for k in range(k_used):
        if collapsed and k != channel:
            continue
        mu_k = scale_t * sigma_t[k] + extra
        emitted = emission_at(media, spectra, medium, value, lam[k])
        state.radiance[i, k] += state.throughput[i, k] * f[k] * math.exp(-(mu_k - mu_c) * gap) * emitted / mixture
