"""A scattering vertex inside a medium (a collision ``media.segment`` chose): light sampling with the
medium's phase function (the shadow ray starts in this medium; ``stages.shadow`` attenuates it through media
and across volume boundaries), then the next direction drawn from the phase function (weight 1), roulette and
the next ray. Its uniforms are the bounce's light, direction and roulette slots, as a surface vertex of
that bounce would use them (a path has one vertex per bounce).
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..light_linking import ALL_SETS, emitter_sets, in_sets
from ..lights.dispatch import sample_light
from ..materials.light_path import after_volume_scatter, emission_sample
from ..sampler import BOUNCE_DIRECTION, BOUNCE_LIGHT, BOUNCE_LIGHT_POINT, bounce_slot, sample_1d, sample_2d
from ..state import CAMERA_PATH, COLLAPSED, LAST_DIFFUSE, LAST_TRANSMISSION, MEDIUM_VERTEX, PREV_DELTA
from ..stages.bounces import path_bounce, shadow_crossings
from ..stages.nee import FAR, SHADOW_SHORTEN
from ..stages.queue import push_ray, queue_shadow
from ..stages.roulette import survives
from ..warps import power_heuristic
from .phase import medium_phase_sample, medium_phase_value

#: The receiver light set of a medium vertex: Prism's media belong to materials, not objects, so a medium
#: receives light as an object no linking singles out (set 0); Cycles uses the volume's object.
MEDIUM_RECEIVER = 0


@inlined
def _light_through_medium(state, i, p, d_in, lights, materials, spectra, geometry, settings, depth, shadows, slot,
                          shading):
    """Queue the light-sampled contribution of medium vertex ``p`` at ``slot`` of ``shadows``; 1 if queued."""
    ps, sample = state.seed[i], state.sample[i]
    u_select = sample_1d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_LIGHT))
    u1, u2 = sample_2d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_LIGHT_POINT))
    li = shading.li
    if settings.light_path:
        emission_sample(shading.registers, state, i)
    wi, dist, pdf_light, delta, group, emitter = sample_light(lights, materials, spectra, geometry, p, u_select, u1,
                                                              u2, state.wavelength[i], li, shading.emitter_rows,
                                                              shading.registers, state.time[i])
    if not pdf_light > 0.0:
        return 0
    shadow_sets = ALL_SETS
    if settings.light_linking or settings.shadow_linking:
        light_sets, shadow_sets = emitter_sets(lights, emitter)
        if settings.light_linking and not in_sets(light_sets, MEDIUM_RECEIVER):
            return 0
        delta = delta or shadow_sets != ALL_SETS  # counted by light sampling alone (``light_linking``)
    phase = medium_phase_value(materials.media, state.medium[i], d_in[0] * wi[0] + d_in[1] * wi[1] + d_in[2] * wi[2])
    weight = 1.0 if (delta or not settings.use_mis) else power_heuristic(pdf_light, phase)
    scale = weight * phase / pdf_light
    contribution = shadows.contribution[slot]
    any_light = False
    for k in range(li.shape[0]):
        contribution[k] = state.throughput[i, k] * li[k] * scale
        any_light = any_light or contribution[k] > 0.0
    distance = dist * (1.0 - SHADOW_SHORTEN) if math.isfinite(dist) else FAR
    if not any_light:
        return 0
    return queue_shadow(shadows, slot, i, p, wi, distance, group, state.medium[i], shadow_sets,
                        shadow_crossings(state, i, settings))


@inlined
def scatter_in_medium(state, i, lights, materials, spectra, geometry, settings, depth, next_rays, queued, shadows,
                      shadowed, shading, rejected):
    """Path ``i`` scatters in its medium at distance ``hit_t`` along its ray. Returns (rays queued, shadow
    rays queued): 0 or 1 each, written at ``next_rays[queued]`` and ``shadows[shadowed]``."""
    state.flags[i] &= ~MEDIUM_VERTEX
    t = state.hit_t[i]
    d_in = (state.direction[i, 0], state.direction[i, 1], state.direction[i, 2])
    p = (state.origin[i, 0] + t * d_in[0], state.origin[i, 1] + t * d_in[1], state.origin[i, 2] + t * d_in[2])
    lit = 0
    if lights.select_prob.shape[0] > 0:
        lit = _light_through_medium(state, i, p, d_in, lights, materials, spectra, geometry, settings, depth,
                                    shadows, shadowed, shading)
    u1, u2 = sample_2d(settings.sampler, state.seed[i], state.sample[i], bounce_slot(depth, BOUNCE_DIRECTION))
    d_out, pdf = medium_phase_sample(materials.media, state.medium[i], d_in, u1, u2)
    state.flags[i] &= ~(CAMERA_PATH | PREV_DELTA | LAST_DIFFUSE | LAST_TRANSMISSION)
    if settings.light_path or settings.kind_limits:
        after_volume_scatter(state, i)
    if not (pdf > 0.0 and survives(state, i, depth, path_bounce(state, i, depth), settings,
                                            state.flags[i] & COLLAPSED != 0)):
        return 0, lit
    state.prev_pdf[i] = pdf
    state.min_pdf[i] = min(state.min_pdf[i], pdf)  # a phase sample counts for Filter Glossy, as in Cycles
    for c in range(3):
        state.mis_origin[i, c] = p[c]
    if settings.light_linking or settings.shadow_linking:
        state.receiver[i] = MEDIUM_RECEIVER
    pushed = push_ray(state, next_rays, queued, i, p, d_out)
    rejected[0] += 1 - pushed
    return pushed, lit
