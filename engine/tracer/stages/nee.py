"""Light sampling (next-event estimation) at a path vertex: one light chosen ∝ power, one point on it,
the BSDF evaluated toward it, the power heuristic against BSDF sampling; the result waits in the shadow
queue until its shadow ray is traced (``stages.shadow``).

Called by the shading kernel for each vertex (the material is evaluated there once for both light and
BSDF sampling; a separate pass would evaluate it twice).
"""

from __future__ import annotations

import math

from ..bsdf.dispatch import bsdf_evaluate
from ..catcher_lights import excluded_from_catcher
from ..geometry import leave_surface
from ..jit import inlined, kernel
from ..light_linking import ALL_SETS, emitter_sets, in_sets
from ..lights.dispatch import sample_light
from ..sampler import BOUNCE_LIGHT, BOUNCE_LIGHT_POINT, bounce_slot, sample_1d, sample_2d
from ..state import DIRECT_SAMPLED
from ..terminator import lifted_ray, terminator_lift
from ..vec3 import to_local
from ..warps import power_heuristic
from .bounces import path_bounce, shadow_crossings
from .clamp import clamp_factor
from .pass_writes import lobe_shares
from .queue import queue_shadow

SHADOW_SHORTEN = 1e-4  # shadow rays stop this fraction short of the light sample
FAR = 1e30  # tmax of shadow rays toward distant lights (float32-representable)


@kernel
def consistent(cos_og, cos_ig, wo_z, wi_z):
    """Reflection must stay on wo's side of the geometric surface and transmission cross it."""
    return (wo_z * wi_z > 0.0) == (cos_og * cos_ig > 0.0)


@inlined
def sample_direct(state, i, vertex, bsdf, lights, materials, spectra, geometry, settings, depth, shadows, slot, li, f,
                  scratch, passes, layout, shading):
    """Queue the light-sampled contribution of path ``i``'s ``vertex`` (``surface_vertex.SurfaceVertex``) with
    its material ``bsdf`` (``surface_vertex.ResolvedBsdf``) at ``slot`` of ``shadows``; returns 1 if queued, else
    0. ``shading`` (``state.ShadingScratch``) lends an emissive program its registers and rows. As in Cycles,
    the light's side of the geometric surface is left to the shadow ray (``surface_vertex``); the closures
    apply Cycles' bump shadowing test themselves (``bsdf.closure_frame``)."""
    p, ng, frame, wo_l = vertex.p, vertex.ng, vertex.frame, vertex.wo_l
    rows, spectral, eta, count, collapsed = bsdf
    ps = state.seed[i]
    sample = state.sample[i]
    u_select = sample_1d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_LIGHT))
    u1, u2 = sample_2d(settings.sampler, ps, sample, bounce_slot(depth, BOUNCE_LIGHT_POINT))
    lam = state.wavelength[i]
    wi, dist, pdf_light, delta, group, emitter = sample_light(lights, materials, spectra, geometry, p, u_select, u1,
                                                              u2, lam, li, shading.emitter_rows, shading.registers,
                                                              state.time[i])
    if not pdf_light > 0.0 or excluded_from_catcher(state, i, settings, lights, emitter):
        return 0
    shadow_sets = ALL_SETS
    if settings.light_linking or settings.shadow_linking:
        light_sets, shadow_sets = emitter_sets(lights, emitter)
        if settings.light_linking and not in_sets(light_sets, lights.links.receiver_set[state.hit_triangle[i]]):
            return 0
        # a shadow-linked emitter is counted by light sampling alone (``light_linking``)
        delta = delta or shadow_sets != ALL_SETS
    wi_l = to_local(wi, frame[0], frame[1], frame[2])
    pdf_bsdf = bsdf_evaluate(rows, spectral, eta, count, wo_l, wi_l, lam, state.hero[i], collapsed, f, scratch)
    weight = 1.0 if (delta or not settings.use_mis) else power_heuristic(pdf_light, pdf_bsdf)
    scale = weight * abs(wi_l[2]) / pdf_light
    contribution = shadows.contribution[slot]
    any_light = False
    for k in range(li.shape[0]):
        contribution[k] = state.throughput[i, k] * f[k] * li[k] * scale
        any_light = any_light or contribution[k] > 0.0
    if not any_light:
        return 0
    if settings.clamping:
        factor = clamp_factor(settings, state, i, contribution, path_bounce(state, i, depth) > 0)
        for k in range(li.shape[0]):
            contribution[k] *= factor
    triangle = state.hit_triangle[i]
    # Cycles' shadow terminator Geometry Offset: smooth triangles start the ray on their smooth surface
    lift = terminator_lift(geometry, triangle, state.hit_u[i], state.hit_v[i], ng, vertex.ns, wi, state.time[i])
    start, toward, dist = lifted_ray(p, lift, wi, dist)
    origin, skipped = leave_surface(geometry, triangle, state.hit_u[i], start, ng, toward, state.time[i])
    distance = (dist - skipped) * (1.0 - SHADOW_SHORTEN) if math.isfinite(dist) else FAR
    # the medium: the path's; the shading stage corrects it where the surface bounds a medium
    if not queue_shadow(shadows, slot, i, origin, toward, distance, group, state.medium[i], shadow_sets,
                        shadow_crossings(state, i, settings)):
        return 0
    if layout.light >= 0 and state.flags[i] & DIRECT_SAMPLED:  # the light's direction splits Direct light
        lobe_shares(rows, spectral, eta, count, wo_l, wi_l, lam, state.hero[i], collapsed, scratch[0],
                    passes.split[i, 0])
    return 1
