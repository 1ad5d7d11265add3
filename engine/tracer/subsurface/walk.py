"""The random walk of a path under a subsurface closure (Cycles' ``subsurface_random_walk``), per wavelength.

From the entry point the path flies through the closure's medium (``coefficients``): at each step a carried
wavelength c is chosen with probability ∝ |throughput × α| (one-sample MIS, balance heuristic, as Cycles does
over its three channels), a direction (after the first step) from the phase function or, part of the time,
guided toward the entry surface (``guiding``, as Cycles), a distance drawn from σ_t(c) e^(−σ_t(c) s)
(stretched along a guided direction), and the first surface of the same object along the way (other objects
are stepped past, as Cycles' local intersection ignores them) ends the walk there: the exit. Each wavelength
k is weighted by its own f_k over Σ_j P_j p_j, P_j the probability of choosing wavelength j and p_j the
density of the step under it, mixed over the two direction strategies: f_k = σ_s,k T_k(s) for a collision,
T_k(s) for the exit, T = e^(−σ_t s). A collision scatters by Henyey-Greenstein with the closure's anisotropy;
past step 9, isotropically with σ_s reduced to σ_s (1 − g) (similarity, as Cycles). A walk ends unfinished
after 256 steps or once its throughput falls below 1e-6 (Cycles' bounds).

Not done as in Cycles: its first ray's look for the opposite side (and the backward guiding it enables).
"""

from __future__ import annotations

import math

from ..bsdf.closure import C_ETA, C_SSS_ANISOTROPY, C_SSS_METHOD, C_SSS_RADIUS, SSS_SKIN
from ..bsdf.subsurface_entry import MAX_IOR, MIN_IOR
from ..embree.queries import closest_hit
from ..geometry import offset_origin
from ..jit import inlined
from ..materials.hit_inputs import object_row
from ..materials.shader_rays import step_past
from ..media.phase import ISOTROPIC_G, hg_sample, hg_value
from ..sampler import sample_2d, subsurface_slot
from .coefficients import walk_coefficients
from .guiding import diffusion_length, guided_cosine, guided_direction, guided_fraction, guided_pdf

MAX_STEPS = 256
#: Steps after which the walk scatters isotropically with reduced coefficients (Cycles' similarity level).
SIMILARITY_STEPS = 9
#: A walk whose largest throughput falls below this ends (Cycles' ``VOLUME_THROUGHPUT_EPSILON``).
THROUGHPUT_EPSILON = 1e-6
#: Hits of other objects one flight steps past before it gives up.
MAX_FOREIGN_HITS = 16


@inlined
def _own_hit(rays, attributes, own, origin, direction, tmax):
    """(row, t, u, v) of the first surface of object ``own`` along the ray before ``tmax``; row -1: none."""
    travelled = 0.0
    o = origin
    for _ in range(MAX_FOREIGN_HITS):
        hit, t, u, v = closest_hit(rays.caster, o[0], o[1], o[2], direction[0], direction[1], direction[2],
                                   tmax - travelled, rays.time)
        if hit < 0:
            return -1, tmax, 0.0, 0.0
        if object_row(attributes, hit) == own:
            return hit, travelled + float(t), float(u), float(v)
        o, step = step_past(o, direction, float(t))
        travelled += step
        if travelled >= tmax:
            break
    return -1, tmax, 0.0, 0.0


@inlined
def _setup(row, spectral, throughput, sigma_t, alpha):
    """σ_t and α per carried wavelength; the throughput loses the albedo the walk adds back by scattering."""
    g = row[C_SSS_ANISOTROPY]
    skin = row[C_SSS_METHOD] == SSS_SKIN
    ior = min(max(row[C_ETA], MIN_IOR), MAX_IOR)
    for k in range(throughput.shape[0]):
        if throughput[k] == 0.0:
            sigma_t[k], alpha[k] = 1.0, 0.0
            continue
        albedo = spectral[0, k]
        sigma_t[k], alpha[k], factor = walk_coefficients(albedo, row[C_SSS_RADIUS] * spectral[1, k], g, skin, ior)
        throughput[k] = throughput[k] / albedo * factor if albedo > 0.0 else 0.0


@inlined
def _phase_pdf(d_from, d_to, g):
    """The density per steradian with which ``hg_sample`` draws ``d_to`` after ``d_from``."""
    if abs(g) < ISOTROPIC_G:
        return 0.25 / math.pi
    return hg_value(d_from[0] * d_to[0] + d_from[1] * d_to[1] + d_from[2] * d_to[2], g)


@inlined
def _flight_density(sigma, t, exits):
    """The density (a collision at ``t``) or probability (no collision before the exit at ``t``) of a flight
    drawn with extinction ``sigma``."""
    transmittance = math.exp(-sigma * t)
    return transmittance if exits else sigma * transmittance


@inlined
def random_walk(rays, attributes, own, row, spectral, p, ng, direction, throughput, scratch):
    """Walk from ``p`` (camera-relative, on object ``own``'s surface of geometric normal ``ng``) along
    ``direction`` (into the surface) with the closure ``row`` / ``spectral`` resolved at the entry;
    ``throughput`` [K] (the path's, after the entry's weight) is updated in place. ``rays`` is the path's
    ``materials.shader_rays.ShaderRays``; ``scratch`` three float64 [K] arrays. Returns (exit row or -1, u, v, point,
    direction of the last flight)."""
    k_count = throughput.shape[0]
    sigma_t, alpha, channel_pdf = scratch[0], scratch[1], scratch[2]
    _setup(row, spectral, throughput, sigma_t, alpha)
    g = row[C_SSS_ANISOTROPY]
    # Guided toward the entry surface's outward normal (``ng`` faces the side the path came from), with the
    # diffusion length of the most scattering wavelength (Cycles: too low a length gives fireflies).
    most = 0.0
    for k in range(k_count):
        most = max(most, alpha[k])
    nu = diffusion_length(most) if most > 0.0 else math.inf
    log_ratio = math.log((nu + 1.0) / (nu - 1.0)) if 1.0 < nu < math.inf else 0.0
    length = math.sqrt(ng[0] * ng[0] + ng[1] * ng[1] + ng[2] * ng[2])
    n = (ng[0] / length, ng[1] / length, ng[2] / length)
    position = offset_origin(p, ng, direction)
    d = direction
    for step in range(MAX_STEPS):
        similar = step > SIMILARITY_STEPS
        g_step = 0.0 if similar else g
        total = 0.0
        for k in range(k_count):
            channel_pdf[k] = abs(throughput[k] * alpha[k])
            total += channel_pdf[k]
        if not total > 0.0:
            return -1, 0.0, 0.0, position, d
        u_channel, u_distance = sample_2d(rays.kind, rays.seed, rays.sample, subsurface_slot(rays.depth, step, 0))
        target = u_channel * total
        c = k_count - 1
        running = 0.0
        for k in range(k_count):
            running += channel_pdf[k]
            if target < running:
                c = k
                break
        for k in range(k_count):
            channel_pdf[k] /= total
        # The first flight keeps the entry's direction; later ones mix phase sampling with guiding.
        share, guided, stretch, guide_ratio = 0.0, False, 1.0, 0.0
        if step > 0:
            u1, u2 = sample_2d(rays.kind, rays.seed, rays.sample, subsurface_slot(rays.depth, step, 1))
            if log_ratio > 0.0:
                share = guided_fraction(g, similar)
                u_strategy, _ = sample_2d(rays.kind, rays.seed, rays.sample, subsurface_slot(rays.depth, step, 2))
                guided = u_strategy < share
            previous = d
            if guided:
                d = guided_direction(n, guided_cosine(nu, log_ratio, u1), u2)
            else:
                d, _ = hg_sample(d, g_step, u1, u2)
            if share > 0.0:
                mu = d[0] * n[0] + d[1] * n[1] + d[2] * n[2]
                stretch = 1.0 - mu / nu
                guide_ratio = guided_pdf(nu, log_ratio, mu) / _phase_pdf(previous, d, g_step)
        sigma_c = sigma_t[c] * (1.0 - alpha[c] * g) if similar else sigma_t[c]
        if guided:
            sigma_c *= stretch
        t = -math.log(1.0 - u_distance) / sigma_c
        hit, t_hit, u, v = _own_hit(rays, attributes, own, position, d, t)
        exits = hit >= 0
        if exits:
            t = t_hit
        position = (position[0] + t * d[0], position[1] + t * d[1], position[2] + t * d[2])
        mixture = 0.0
        for k in range(k_count):  # the mixture's pdf; channel_pdf[k] then holds wavelength k's own f
            s_t = sigma_t[k] * (1.0 - alpha[k] * g) if similar else sigma_t[k]
            density = _flight_density(s_t, t, exits)
            if share > 0.0:  # phase-sampled and guided steps, relative to the phase function's density
                density = (1.0 - share) * density + share * guide_ratio * _flight_density(stretch * s_t, t, exits)
            mixture += channel_pdf[k] * density
            s_s = s_t - sigma_t[k] * (1.0 - alpha[k])  # σ_s (1 − g) past the similarity level, else σ_s
            transmittance = math.exp(-s_t * t)
            channel_pdf[k] = transmittance if exits else s_s * transmittance
        largest = 0.0
        for k in range(k_count):
            throughput[k] = throughput[k] * channel_pdf[k] / mixture if mixture > 0.0 else 0.0
            largest = max(largest, throughput[k])
        if exits:
            return hit, u, v, position, d
        if largest < THROUGHPUT_EPSILON:
            break
    return -1, 0.0, 0.0, position, d
