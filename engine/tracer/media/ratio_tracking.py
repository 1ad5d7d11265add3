"""Transmittance of a shadow ray through a grid medium by ratio tracking (Novák, Selle & Jarosz 2014,
"Residual ratio tracking for estimating attenuation in participating media", §3): tentative collisions at
the rate μ = D_max max_k σ_t,k (one rate for every carried wavelength, so one walk serves them all; D_max the
majorant of the block the walk crosses, ``brick_majorants``: empty blocks cost no step) and, at each, every
wavelength's estimate multiplied by 1 − D(x) σ_t,k / μ. The product is an unbiased estimate of
exp(-∫ D σ_t,k ds) per wavelength, in [0, 1]. The walk stops early once every estimate is 0.

A shadow ray may take any number of steps, so its numbers are hashed (``sampler.INDEPENDENT``) from the
path's sample, a key of the ray (its layer and where it starts) and the step. A walk that needs more than
``density_grid.MAX_TRACKING_STEPS`` of them counts as opaque.
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..sampler import INDEPENDENT, SLOT_RATIO_TRACKING, hash32, sample_1d
from .coefficients import extinction_at
from .brick_majorants import brick_advance, brick_entry, brick_majorant
from .density_grid import MAX_TRACKING_STEPS
from .grid_lookup import density_along, grid_span, index_ray


@inlined
def ray_key(layer, o):
    """A 32-bit key of a shadow ray: its layer and its origin (metres, to about a micrometre)."""
    key = hash32(layer + 0x51ED27)
    for c in range(3):
        key = hash32(key ^ (int(abs(o[c]) * 1048576.0) & 0xFFFFFFFF))
    return key


@inlined
def ratio_track(media, spectra, medium, wavelengths_nm, o, d, distance_m, values, sigma_t, pixel_seed, sample,
                key):
    """``values[k]`` *= an unbiased estimate of the transmittance of grid medium ``medium`` along ``o`` + s
    ``d``, s in [0, ``distance_m``]. ``sigma_t``: scratch [K]; ``pixel_seed``, ``sample``, ``key``: the
    numbers' stream (``ray_key``)."""
    grids = media.grids
    g = media.grid[medium]
    o2, d2 = index_ray(grids, g, o, d)
    s0, s1 = grid_span(grids, g, o2, d2, distance_m)
    if not s0 < s1:
        return
    largest = 0.0
    for k in range(wavelengths_nm.shape[0]):
        sigma_t[k] = extinction_at(media, spectra, medium, wavelengths_nm[k])
        if values[k] != 0.0:
            largest = max(largest, sigma_t[k])
    if not grids.majorant[g] * largest > 0.0:
        return
    s = s0
    step = 0
    seed = pixel_seed ^ key
    block, following, width, stride = brick_entry(grids, g, o2, d2, s0)
    depth = -math.log1p(-sample_1d(INDEPENDENT, seed, sample, SLOT_RATIO_TRACKING))  # to the next collision
    crossings = 0
    while True:
        if step == MAX_TRACKING_STEPS or crossings == MAX_TRACKING_STEPS:
            for k in range(wavelengths_nm.shape[0]):
                values[k] = 0.0
            return
        end = min(following[0], following[1], following[2], s1)
        mu = brick_majorant(grids, g, block) * largest
        if not depth < mu * (end - s):  # no collision in this block
            if not end < s1:
                return
            depth -= mu * (end - s)
            s = end
            block, following = brick_advance(block, following, width, stride)
            crossings += 1
            continue
        s += depth / mu
        step += 1
        depth = -math.log1p(-sample_1d(INDEPENDENT, seed, sample, SLOT_RATIO_TRACKING + step))
        density = density_along(grids, g, o2, d2, s)
        if density <= 0.0:
            continue
        alive = False
        for k in range(wavelengths_nm.shape[0]):
            values[k] *= max(1.0 - density * sigma_t[k] / mu, 0.0)
            alive = alive or values[k] != 0.0
        if not alive:
            return
