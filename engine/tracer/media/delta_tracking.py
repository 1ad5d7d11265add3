"""A ray segment inside a grid medium (coefficients × a voxel density, ``density_grid``): delta tracking
against the grid's majorant, with the spectral MIS of ``segment`` (one-sample balance heuristic over the
path's wavelengths).

Null-scattering formulation (Miller, Georgiev & Jarosz 2019, "A null-scattering path integral formulation of
light transport", §4-5; Novák et al. 2014 for delta and ratio tracking). With D(x) the density, σ_s, σ_t the
medium's coefficients at density 1 and D_max the largest density of the block of voxels the walk is in
(``brick_majorants``: piecewise constant along the ray, 0 in empty blocks), each wavelength k has the majorant
μ_k = D_max σ_t,k and the null coefficient σ_n,k(x) = μ_k − D(x) σ_t,k >= 0. Along the ray the radiance is
∫ T_maj(s) [σ_s L_s + σ_n L](x_s) ds + T_maj(t) L_surface, T_maj(s) = exp(-μ s): tentative collisions are
drawn at rate μ_c of one wavelength c (chosen uniformly per segment, the hero alone on a collapsed path), and
at each one the path scatters with probability D σ_s,c / μ_c, else it goes on (a null collision; absorption
is not an event of its own but weights the path, as ``segment`` treats a homogeneous medium's absorption).

The events (n null collisions at x_1..x_n, then a scattering at x_s, or none before the surface) have, per
wavelength k, the contribution f_k = T_maj,k Π σ_n,k(x_i) [D σ_s,k](x_s) and, for the tracker of wavelength
j, the probability p_j = T_maj,j Π (μ_j − D σ_s,j)(x_i) [D σ_s,j](x_s); the path is weighted by f_k /
((1/K) Σ_j p_j). Both are kept divided by common factors (μ_c and exp(-μ_c s) per step, then the largest p)
so that long walks neither overflow nor underflow: only their ratio matters. T_maj,k = exp(-∫ μ_k) is gathered
block by block: crossing a block's stretch without a collision multiplies f_k and p_k by exp(-(μ_k − μ_c)
length), and the free flight's optical depth carries over into the next block. With a constant density the
expectation is the homogeneous medium's; a pure scatterer of one colour weighs every path exactly 1.

An emitting grid medium adds ``MediaArrays.emission_rate`` to every μ_k (a null rate: σ_n grows by as much)
and gathers its emission at each tentative collision (``grid_emission``), over the span of its density and
temperature grids. A walk that needs more than ``density_grid.MAX_TRACKING_STEPS`` tentative collisions ends
the path (an opaque medium). Equiangular sampling toward lights is not used here (``docs/media.md``).
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..sampler import grid_medium_uniforms, medium_slot, sample_2d
from ..state import COLLAPSED
from .coefficients import coefficients_at
from .brick_majorants import brick_advance, brick_entry, brick_majorant
from .density_grid import MAX_TRACKING_STEPS
from .grid_emission import gather_emission
from .grid_lookup import density_along, grid_span, index_ray


@inlined
def _null_or_scatter(f, p, sigma_t, sigma_s, walk, k_used, density, gap, scatters):
    """Multiply ``f``, ``p`` by one tentative collision's factors (``gap`` after the previous one, divided by
    the chosen channel's exp(-μ_c gap) μ_c), then by the largest p. ``walk``: (medium, channel, collapsed,
    scale_t, extra), μ_k = scale_t σ_t,k + extra."""
    _, channel, collapsed, scale_t, extra = walk
    mu_c = scale_t * sigma_t[channel] + extra
    largest = 0.0
    for k in range(k_used):
        if collapsed and k != channel:
            continue
        mu_k = scale_t * sigma_t[k] + extra
        common = math.exp(-(mu_k - mu_c) * gap) / mu_c
        if scatters:
            f[k] *= common * density * sigma_s[k]
            p[k] *= common * density * sigma_s[k]
        else:
            f[k] *= common * max(mu_k - density * sigma_t[k], 0.0)
            p[k] *= common * max(mu_k - density * sigma_s[k], 0.0)
        largest = max(largest, p[k])
    if largest > 0.0:
        for k in range(k_used):
            if collapsed and k != channel:
                continue  # not carried: left at 1, never grown by the renormalisation
            f[k] /= largest
            p[k] /= largest


@inlined
def _carry(f, p, sigma_t, channel, collapsed, k_used, scale_t, length):
    """Multiply ``f``, ``p`` by a block's stretch of ``length`` without a tentative collision (divided by the
    chosen channel's exp(-μ_c length)): exp(-(μ_k − μ_c) length), μ_k − μ_c = ``scale_t`` (σ_t,k − σ_t,c)."""
    for k in range(k_used):
        if collapsed and k != channel:
            continue
        common = math.exp(-scale_t * (sigma_t[k] - sigma_t[channel]) * length)
        f[k] *= common
        p[k] *= common


@inlined
def track_grid_medium(state, i, t, media, spectra, settings, depth, sigma_t, sigma_s, f, p):
    """Path ``i``'s ray, inside its grid medium, reaches a surface at ``t`` (inf: none). Returns where it
    scatters (< t) or inf, its throughput weighted for that. ``sigma_t``, ``sigma_s``, ``f``, ``p``: scratch
    [K]."""
    medium = state.medium[i]
    grids = media.grids
    g = media.grid[medium]
    lam = state.wavelength[i]
    k_used = lam.shape[0]
    o = (state.origin[i, 0], state.origin[i, 1], state.origin[i, 2])
    d = (state.direction[i, 0], state.direction[i, 1], state.direction[i, 2])
    o2, d2 = index_ray(grids, g, o, d)
    s0, s1 = grid_span(grids, g, o2, d2, t)
    emits = media.emission_strength[medium] > 0.0
    hot = media.emission_grid[medium]
    o3, d3 = o2, d2  # the temperature grid's ray, read only where the medium emits
    if emits and hot >= 0:  # the temperature grid's voxels glow where the density's may not reach
        o3, d3 = index_ray(grids, hot, o, d)
        e0, e1 = grid_span(grids, hot, o3, d3, t)
        if e0 < e1:
            s0, s1 = (min(s0, e0), max(s1, e1)) if s0 < s1 else (e0, e1)
    if not s0 < s1:
        return math.inf  # the ray misses the grid's voxels: density 0 all along, transmittance 1
    coefficients_at(media, spectra, medium, lam, sigma_t, sigma_s)
    collapsed = state.flags[i] & COLLAPSED != 0
    u_channel, u_distance = sample_2d(settings.sampler, state.seed[i], state.sample[i], medium_slot(depth))
    channel = state.hero[i] if collapsed else min(int(u_channel * k_used), k_used - 1)
    extra = media.emission_rate[medium] if emits else 0.0
    for k in range(k_used):
        f[k] = 1.0
        p[k] = 1.0
    s = s0
    collision = math.inf
    step = 0
    crossings = 0
    block, following, width, stride = brick_entry(grids, g, o2, d2, s0)
    flight = -math.log1p(-u_distance)  # the free flight's optical depth at the tracker's rate
    while True:
        if step == MAX_TRACKING_STEPS or crossings == MAX_TRACKING_STEPS:
            for k in range(k_used):
                state.throughput[i, k] = 0.0
            return math.inf
        end = min(following[0], following[1], following[2], s1)
        scale_t = brick_majorant(grids, g, block)  # μ_k = scale_t σ_t,k + extra in this block
        mu_c = scale_t * sigma_t[channel] + extra
        if not flight < mu_c * (end - s):  # no tentative collision in this block before the far side or surface
            _carry(f, p, sigma_t, channel, collapsed, k_used, scale_t, end - s)
            if not end < s1:
                break
            flight -= mu_c * (end - s)
            s = end
            block, following = brick_advance(block, following, width, stride)
            crossings += 1
            continue
        walk = (medium, channel, collapsed, scale_t, extra)
        gap = flight / mu_c
        s += gap
        density = density_along(grids, g, o2, d2, s)
        if emits:
            value = density_along(grids, hot, o3, d3, s) if hot >= 0 else 0.0
            gather_emission(state, i, media, spectra, value, walk, f, p, sigma_t, gap)
        u_event, u_distance = grid_medium_uniforms(settings.sampler, state.seed[i], state.sample[i], depth, step)
        step += 1
        scatters = u_event * mu_c < density * sigma_s[channel]
        _null_or_scatter(f, p, sigma_t, sigma_s, walk, k_used, density, gap, scatters)
        if scatters:
            collision = s
            break
        flight = -math.log1p(-u_distance)
    mixture = 0.0
    for k in range(k_used):
        if collapsed and k != channel:
            continue
        mixture += p[k]
    if not collapsed:
        mixture /= k_used
    for k in range(k_used):
        state.throughput[i, k] = state.throughput[i, k] * f[k] / mixture if mixture > 0.0 else 0.0
    return collision
