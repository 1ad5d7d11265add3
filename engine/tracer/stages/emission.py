"""Stage 2: emission found by this bounce's rays, and which paths go on to a surface.

For each queued ray: a hittable light closer than Embree's hit (spheres, area lights; Blender lights
are invisible to camera rays), an emissive triangle, or an escape (world background, sun discs) adds
its radiance × throughput × MIS weight. Light pdfs are measured from the path's ``mis_origin`` (the
last vertex before any free-standing film it crossed; films do not bend rays). A path that hits a light
ends there; one that hits a surface is listed for shading unless it has used its last bounce.
"""

from __future__ import annotations

import math

from ..jit import inlined, kernel
from ..lights.dispatch import (distant_hit, emitter_group, emitter_pdf, intersect_light, is_distant, light_hit,
                               light_spectrum)
from ..materials.table import MAT_EMISSIVE
from ..spectra.table import spectrum_value
from .mis import emitter_weight
from .passes import camera_slot, deposit, features_done


@inlined
def _add(state, i, factor, sid, spectra, weight, passes, layout, group, slot, albedo):
    scale = factor * weight
    if scale == 0.0:
        return
    for k in range(state.radiance.shape[1]):
        value = state.throughput[i, k] * scale * spectrum_value(spectra, sid, state.wavelength[i, k])
        state.radiance[i, k] += value
        if layout.columns > 0:
            deposit(passes, layout, i, k, value, group, slot, albedo)


@kernel
def emission_kernel(state, rays, count, hit_triangle, hit_t, hit_u, hit_v, geometry, materials, lights, spectra,
                    settings, depth, surface, passes, layout):
    """Add emission for the first ``count`` rays of ``rays``; list the paths that hit a surface in
    ``surface.path`` and return how many. ``passes`` / ``layout``: see ``stages.passes``."""
    shade_next = depth <= settings.max_bounces
    listed = 0
    for j in range(count):
        i = rays.path[j]
        o = (state.origin[i, 0], state.origin[i, 1], state.origin[i, 2])
        d = (state.direction[i, 0], state.direction[i, 1], state.direction[i, 2])
        triangle = hit_triangle[j]
        t = float(hit_t[j]) if triangle >= 0 else math.inf
        light = -1
        if depth > 0 and lights.hittable.shape[0] > 0:
            light, t_light = intersect_light(lights, o, d, t)
            if light >= 0:
                t = t_light
        mis_origin = (state.mis_origin[i, 0], state.mis_origin[i, 1], state.mis_origin[i, 2])
        t_mis = t + (o[0] - mis_origin[0]) * d[0] + (o[1] - mis_origin[1]) * d[1] + (o[2] - mis_origin[2]) * d[2]
        if light >= 0:
            factor, pdf = light_hit(lights, light, mis_origin, d, t_mis)
            _add(state, i, factor, light_spectrum(lights, light), spectra,
                 emitter_weight(state, i, pdf, settings.use_mis), passes, layout, lights.group[light], -1, True)
            if layout.columns > 0:
                features_done(passes, layout, i)
            continue
        if triangle < 0:
            slot = camera_slot(layout, depth, True)
            if lights.world_strength > 0.0:
                _add(state, i, lights.world_strength, lights.world_spectrum, spectra, 1.0, passes, layout,
                     lights.world_group, slot, True)
            if depth > 0:
                for index in range(lights.rows.shape[0] if lights.select_prob.shape[0] > 0 else 0):
                    if is_distant(lights, index):
                        factor, pdf = distant_hit(lights, index, d)
                        if factor > 0.0:
                            _add(state, i, factor, light_spectrum(lights, index), spectra,
                                 emitter_weight(state, i, pdf, settings.use_mis), passes, layout,
                                 lights.group[index], slot, True)
            if layout.columns > 0:
                features_done(passes, layout, i)
            continue
        material = geometry.material[triangle]
        if materials.flags[material] & MAT_EMISSIVE:
            weight = 1.0 if depth == 0 else emitter_weight(state, i, emitter_pdf(lights, triangle, d, t_mis),
                                                          settings.use_mis)
            _add(state, i, materials.emission_strength[material], materials.emission_spectrum[material], spectra,
                 weight, passes, layout, emitter_group(lights, triangle), camera_slot(layout, depth, False), False)
        if shade_next:
            state.hit_triangle[i] = triangle
            state.hit_u[i] = hit_u[j]
            state.hit_v[i] = hit_v[j]
            state.hit_t[i] = t
            surface.path[listed] = i
            listed += 1
    return listed
