"""Stage 2: emission found by this bounce's rays, and which paths go on to a surface.

For each queued ray: every hittable light in front of the surface Embree found (spheres, area lights;
Blender lights are seen by camera rays only when their Camera ray visibility is on), an emissive
triangle, or an escape (the world's background, sun discs) adds its radiance × throughput × MIS
weight. Light pdfs are measured from the path's ``mis_origin`` (the last vertex before any
free-standing film it crossed; films do not bend rays). Lights are transparent, as in Cycles: a ray
that meets one adds its light and goes on to whatever lies behind it. A path that hits a surface is
listed for shading unless it has used its last bounce (past Max Bounces only a cut-out or a film is shaded,
which the path may still go through; past Transparent Max Bounces none is: ``stages.bounces``).

Film transparency (Cycles'): a camera path (``CAMERA_PATH``: no scattering yet but transparent glass)
that escapes into a transparent film's background, or meets a holdout, becomes see-through by its
throughput's mean (``transparency``) and brings no light from there.

A ray inside a medium (``media.segment``) first adds the medium's emission along it and may scatter
before the surface: the path is then listed as a medium vertex (``MEDIUM_VERTEX``, at ``hit_t``).
"""

from __future__ import annotations

import math

from ..jit import inlined, kernel
from ..light_linking import hit_counts
from ..lights import environment
from ..lights.dispatch import (distant_hit, emitter_group, emitter_pdf, environment_pdf, is_distant, light_distance,
                               light_hit, light_spectrum, seen_by_camera)
from ..materials.emitters import emission_at
from ..materials.light_path import path_ray
from ..materials.shader_rays import ShaderRays
from ..media.segment import cross_medium
from ..materials.table import MAT_EMISSION_VARIES, MAT_EMISSIVE, MAT_NULL, MAT_TRANSPARENT
from ..spectra.table import spectrum_value
from ..state import CAMERA_PATH, MEDIUM_VERTEX, PREV_DELTA, SUBSURFACE_EXIT
from ..visibility import HOLDOUT
from .bounces import bounces_left, ends_at_next_surface, path_bounce
from .clamp import clamp_factor
from .mis import emitter_weight
from .data_pass_writes import camera_escape
from .pass_writes import camera_slot, deposit, features_done
from .see_through import mean_throughput
from .shadow_catcher import background_seen, share_emission, split_at_catcher, splits_here


@inlined
def _add(state, i, factor, sid, spectra, weight, passes, layout, group, slot, albedo, settings, bounce, tmp):
    scale = factor * weight
    if scale == 0.0:
        return
    if settings.clamping:
        for k in range(state.radiance.shape[1]):
            tmp[k] = state.throughput[i, k] * scale * spectrum_value(spectra, sid, state.wavelength[i, k])
        scale *= clamp_factor(settings, state, i, tmp, bounce > 1)
    for k in range(state.radiance.shape[1]):
        value = state.throughput[i, k] * scale * spectrum_value(spectra, sid, state.wavelength[i, k])
        state.radiance[i, k] += value
        if layout.columns > 0:
            deposit(passes, layout, i, k, value, group, slot, albedo)


@inlined
def _add_lights_along(state, i, o, d, t, mis_origin, lights, spectra, settings, depth, bounce, passes, layout, tmp):
    """Every hittable light between the ray's origin and distance ``t`` adds its emission (step ``depth``, the
    path's ``bounce``: ``stages.bounces``)."""
    offset = (o[0] - mis_origin[0]) * d[0] + (o[1] - mis_origin[1]) * d[1] + (o[2] - mis_origin[2]) * d[2]
    for h in range(lights.hittable.shape[0]):
        index = lights.hittable[h]
        if bounce == 0 and not seen_by_camera(lights, index):
            continue
        t_light = light_distance(lights, index, o, d)
        if t_light < t and hit_counts(state, i, settings, lights, index):
            factor, pdf = light_hit(lights, index, mis_origin, d, t_light + offset)
            _add(state, i, factor, light_spectrum(lights, index), spectra,
                 emitter_weight(state, i, pdf, settings.use_mis), passes, layout, lights.group[index],
                 camera_slot(state, i, layout, False), True, settings, bounce, tmp)


@inlined
def _see_through(state, i):
    """Path ``i`` is transparent by its throughput's mean from here on."""
    state.transparency[i] += mean_throughput(state, i)


@inlined
def _add_background(state, i, d, lights, spectra, settings, depth, bounce, passes, layout, tmp):
    """The world's background and the sun discs seen by an escaping ray."""
    if settings.film_transparent and state.flags[i] & CAMERA_PATH:
        _see_through(state, i)
        return
    slot = camera_slot(state, i, layout, True)
    backplate = lights.backplate and state.flags[i] & CAMERA_PATH != 0  # Light Path ▸ Is Camera Ray's background
    env = lights.camera_environment if backplate else lights.environment
    if env.kind != environment.ENV_NONE:
        weight = 1.0
        if not backplate and lights.environment_index >= 0 and not state.flags[i] & PREV_DELTA:
            weight = emitter_weight(state, i, environment_pdf(lights, d), settings.use_mis)
        if weight > 0.0:
            fp = environment.footprint(env, d)
            if settings.clamping:
                for k in range(state.radiance.shape[1]):
                    tmp[k] = state.throughput[i, k] * weight * environment.value(env, spectra, fp,
                                                                                 state.wavelength[i, k])
                weight *= clamp_factor(settings, state, i, tmp, bounce > 1)
            for k in range(state.radiance.shape[1]):
                value = state.throughput[i, k] * weight * environment.value(env, spectra, fp, state.wavelength[i, k])
                state.radiance[i, k] += value
                background_seen(state, i, settings, passes, k, value)
                if layout.columns > 0:
                    deposit(passes, layout, i, k, value, lights.world_group, slot, True)
    for index in range(lights.rows.shape[0] if lights.select_prob.shape[0] > 0 else 0):
        if (is_distant(lights, index) and (bounce > 0 or seen_by_camera(lights, index))
                and hit_counts(state, i, settings, lights, index)):
            factor, pdf = distant_hit(lights, index, d)
            if factor > 0.0:
                _add(state, i, factor, light_spectrum(lights, index), spectra,
                     emitter_weight(state, i, pdf, settings.use_mis), passes, layout, lights.group[index], slot,
                     True, settings, bounce, tmp)


@kernel
def emission_kernel(state, rays, count, hit_triangle, hit_t, hit_u, hit_v, geometry, materials, lights, spectra,
                    settings, depth, surface, passes, layout, scratch, caster):
    """Add emission for the first ``count`` rays of ``rays``; list the paths that hit a surface in
    ``surface.path`` and return how many. ``passes`` / ``layout``: see ``stages.pass_writes``; ``scratch``
    (``state.ShadingScratch``) serves materials whose emission varies over the surface."""
    listed = 0
    for j in range(count):
        i = rays.path[j]
        bounce = path_bounce(state, i, depth)
        scatters = bounces_left(state, i, bounce, settings)  # the path may scatter at its next vertex
        if state.flags[i] & SUBSURFACE_EXIT:  # the hit is a random walk's exit, stored already (``subsurface``)
            if scatters:
                surface.path[listed] = i
                listed += 1
            else:
                state.flags[i] &= ~SUBSURFACE_EXIT
            continue
        o = (state.origin[i, 0], state.origin[i, 1], state.origin[i, 2])
        d = (state.direction[i, 0], state.direction[i, 1], state.direction[i, 2])
        triangle = hit_triangle[j]
        t = float(hit_t[j]) if triangle >= 0 else math.inf
        mis_origin = (state.mis_origin[i, 0], state.mis_origin[i, 1], state.mis_origin[i, 2])
        if settings.has_media and state.medium[i] >= 0:
            collision = cross_medium(state, i, t, materials.media, spectra, settings, depth, scratch.mix[0],
                                     scratch.mix[1], lights, scratch.f, scratch.li)
            if collision < t:  # the path scatters in its medium: a vertex for the shading stage
                if lights.hittable.shape[0] > 0:
                    _add_lights_along(state, i, o, d, collision, mis_origin, lights, spectra, settings, depth, bounce,
                                      passes, layout, scratch.weight)
                if layout.columns > 0:
                    features_done(passes, layout, i)
                if scatters:
                    state.flags[i] |= MEDIUM_VERTEX
                    state.hit_t[i] = collision
                    surface.path[listed] = i
                    listed += 1
                continue
        if lights.hittable.shape[0] > 0:
            _add_lights_along(state, i, o, d, t, mis_origin, lights, spectra, settings, depth, bounce, passes,
                              layout, scratch.weight)
        if triangle < 0:
            _add_background(state, i, d, lights, spectra, settings, depth, bounce, passes, layout, scratch.weight)
            if layout.columns > 0:
                features_done(passes, layout, i)
                camera_escape(state, passes, layout, i)
            continue
        if geometry.flags[triangle] & HOLDOUT and state.flags[i] & CAMERA_PATH:
            _see_through(state, i)
            if layout.columns > 0:
                features_done(passes, layout, i)
            continue
        material = geometry.material[triangle]
        # past Max Bounces a path still goes through cut-outs and films; past Transparent Max Bounces it ends here
        shade_next = (not ends_at_next_surface(state, i, settings)
                      and (scatters or materials.flags[material] & (MAT_TRANSPARENT | MAT_NULL) != 0))
        copy = -1  # a shadow catcher's copy of the path (``stages.shadow_catcher``)
        if settings.shadow_catcher and shade_next and splits_here(state, i, geometry, triangle):
            copy = split_at_catcher(state, i, triangle, hit_u[j], hit_v[j], t, lights, spectra, passes, layout, d)
        if materials.flags[material] & MAT_EMISSIVE and hit_counts(state, i, settings, lights,
                                                                   lights.rows.shape[0] + triangle):
            t_mis = t + (o[0] - mis_origin[0]) * d[0] + (o[1] - mis_origin[1]) * d[1] + (o[2] - mis_origin[2]) * d[2]
            light_pdf = emitter_pdf(lights, geometry, triangle, d, t_mis, state.time[i])
            weight = 1.0 if bounce == 0 else emitter_weight(state, i, light_pdf, settings.use_mis)
            group, slot = emitter_group(lights, triangle), camera_slot(state, i, layout, False)
            if materials.flags[material] & MAT_EMISSION_VARIES:
                radiance = scratch.li
                if settings.light_path:
                    path_ray(scratch.registers, state, i, t)
                traced = ShaderRays(caster, settings.sampler, state.seed[i], state.sample[i], depth, state.time[i],
                                    state.min_pdf[i])  # the same rays as the shading of this hit traces
                emission_at(materials, spectra, geometry, material, triangle, float(hit_u[j]), float(hit_v[j]), state.time[i],
                            (-d[0], -d[1], -d[2]), state.wavelength[i], scratch.rows, scratch.registers, radiance,
                            traced)
                if settings.clamping:
                    for k in range(state.radiance.shape[1]):
                        scratch.weight[k] = state.throughput[i, k] * weight * radiance[k]
                    weight *= clamp_factor(settings, state, i, scratch.weight, bounce > 1)
                for k in range(state.radiance.shape[1]):
                    value = state.throughput[i, k] * weight * radiance[k]
                    state.radiance[i, k] += value
                    if layout.columns > 0:
                        deposit(passes, layout, i, k, value, group, slot, False)
            else:
                _add(state, i, materials.emission_strength[material], materials.emission_spectrum[material],
                     spectra, weight, passes, layout, group, slot, False, settings, bounce, scratch.weight)
        if shade_next:
            state.hit_triangle[i] = triangle
            state.hit_u[i] = hit_u[j]
            state.hit_v[i] = hit_v[j]
            state.hit_t[i] = t
            surface.path[listed] = i
            listed += 1
            if copy >= 0:
                share_emission(state, i, copy, passes)
                surface.path[listed] = copy
                listed += 1
    return listed
