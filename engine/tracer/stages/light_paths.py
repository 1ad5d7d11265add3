"""Light tracing for caustics: paths that start on the lights, cross specular objects and are seen by
the camera where they first meet a surface that is not purely specular.

A light path (a ``PathState`` row like a camera path: its wavelengths, hero, throughput β) starts with
``lights.emission.sample_emission`` — aimed at the specular objects — and at each hit:

- on a purely specular material (``MAT_DELTA``) it samples the BSDF and goes on, β × f cos / pdf
  carried as flux: refraction without the 1/η'² that radiance takes (``eta_scale`` undoes it), and
  Veach's shading-normal factor |wo·ns| |wi·ng| / (|wo·ng| |wi·ns|) for the adjoint; a dispersive glass
  keeps the hero wavelength, as on camera paths; crossing a film straight through is a null event.
- on anything else it ends, and if it crossed at least one specular vertex (``LIGHT_SPECULAR``: the path
  is L S+ D, ``stages.caustic_split``) it connects to the camera: a lens point, the pixel
  (``camera_connection``), the BSDF toward the camera, and β f |cos_s in| / |cos_g in| · |cos_g cam| / d²
  · W as the pixel's spectral radiance, waiting for its visibility ray (``LIGHT_CONNECTED``).

A light path has at most one splat, so the chunk's splats come out in path order (``connection_splats``).
Roulette compares β with its start (``eta_scale`` holds 1 / the largest starting weight), so dim and
bright lights alike survive while they keep their share. The spot falloff is a function of the point
a light reaches (as for camera paths), so it is applied at the first hit.

Light paths draw from their own stream of uniforms (the sampler seeded with the render's seed salted),
numbered like camera paths: stream = the pass's path index // samples per pixel, sample = the sample's
number, so sample chunks of a render trace the same light paths as one render.

With motion blur a light path has a ray time like a camera path (drawn from the shutter curve in a slot of its
own): its rays meet the geometry where it stands then, it leaves an emitting triangle where that stands then,
and its connection goes to the camera where it is then.
"""

from __future__ import annotations

import math

from ..bsdf.dispatch import bsdf_evaluate
from ..geometry import offset_origin, surface_at
from ..jit import inlined, kernel
from ..lights.emission import sample_emission
from ..lights.point import spot_falloff
from ..lights.row import L_KIND, POINT, SPHERE
from ..materials.closure_normals import orient_closures
from ..materials.surface import shade_surface
from ..materials.table import MAT_CLOSURE_NORMALS, MAT_DELTA, MAT_DISPERSIVE, MAT_HAIR, MAT_NULL, MAT_ONE_SIDED
from ..sampler import pixel_seed, sample_1d, sample_2d
from ..spectra.wavelength_sampling import radiance_to_rgb
from ..state import COLLAPSED, LIGHT_CONNECTED, LIGHT_SPECULAR
from ..vec3 import tangents, to_local
from .camera import draw_wavelengths
from .camera_connection import connect_to_camera
from .camera_motion import shutter_time
from .nee import SHADOW_SHORTEN, consistent
from .queue import push_ray
from .roulette import survives
from .shade import collapse_to_hero, sample_scattering

STREAM_SALT = 0x4C16A7E5  # light paths' sampler seed = the render's seed ^ this
# Slots of the light paths' own decisions, far above any bounce slot (bounces use the usual slots).
SLOT_SELECT = 1 << 20  # 1-D: which light
SLOT_POSITION = SLOT_SELECT + 1  # 2-D: where on it
SLOT_TARGET = SLOT_SELECT + 2  # 1-D: which specular object to aim at
SLOT_DIRECTION = SLOT_SELECT + 3  # 2-D: direction in its cone (or a sun disc's direction)
SLOT_CAMERA_LENS = SLOT_SELECT + 4  # 2-D: lens point of the connection
SLOT_CAMERA_FILTER = SLOT_SELECT + 5  # 2-D: which pixel under the filter
SLOT_PATH_TIME = SLOT_SELECT + 6  # 1-D: the path's ray time in the shutter (motion blur)


@kernel
def emit_kernel(state, rays, light_of_path, lights, materials, spectra, geometry, targets, ws, settings, first, count,
                samples_per_pixel, first_sample, scratch, shutter_times):
    """Start light paths ``first .. first + count`` of the pass in rows 0 .. count-1 and queue their rays;
    returns the number queued (paths whose light sends nothing toward the targets end at once). With motion blur
    (``shutter_times``, the camera's, not empty) each path draws its ray time from the shutter as a camera path
    does: its bounces, its connection and the camera it connects to are where they are then."""
    queued = 0
    k = state.throughput.shape[1]
    for i in range(count):
        p = first + i
        sample = first_sample + p % samples_per_pixel
        ps = pixel_seed(p // samples_per_pixel, settings.seed ^ STREAM_SALT)
        state.pixel[i] = -1
        state.sample[i] = sample
        state.seed[i] = ps
        state.flags[i] = 0
        state.medium[i] = -1
        state.time[i] = 0.5  # a still scene: read by nothing
        if shutter_times.shape[0] > 0:
            state.time[i] = shutter_time(shutter_times, sample_1d(settings.sampler, ps, sample, SLOT_PATH_TIME))
        state.prev_pdf[i] = 0.0
        state.radiance[i, :] = 0.0
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        origin, direction, light = sample_emission(
            lights, materials, spectra, geometry, targets, sample_1d(settings.sampler, ps, sample, SLOT_SELECT),
            sample_2d(settings.sampler, ps, sample, SLOT_POSITION),
            sample_1d(settings.sampler, ps, sample, SLOT_TARGET),
            sample_2d(settings.sampler, ps, sample, SLOT_DIRECTION), state.wavelength[i], state.throughput[i],
            scratch.emitter_rows, scratch.registers, state.time[i])
        light_of_path[i] = light
        largest = 0.0
        for c in range(k):
            largest = max(largest, state.throughput[i, c])
        if not (largest > 0.0 and math.isfinite(largest)):
            continue
        state.eta_scale[i] = 1.0 / largest
        queued += push_ray(state, rays, queued, i, origin, direction)
    return queued


@inlined
def _resolve(hit, p, ng, ns, wo, backfacing, mflags, lam, hero, rows, spectral, eta, registers):
    """The material of ``hit`` (see ``connect``) at ``p`` seen along ``wo``: (closure count, shading normal
    facing ``wo``, unless the material is one-sided)."""
    materials, spectra, geometry, material, triangle, u, v, glass_clamps = hit
    facing_ng = (-ng[0], -ng[1], -ng[2]) if backfacing else ng
    facing_ns = (-ns[0], -ns[1], -ns[2]) if backfacing else ns
    closures, n = shade_surface(materials, spectra, geometry, material, triangle, u, v, p, facing_ng, facing_ns, wo,
                                backfacing, lam, hero, rows, spectral, eta, registers, glass_clamps,
                                None)  # light tracing is off where materials trace (``analysis``)
    flipped = backfacing and mflags & MAT_ONE_SIDED != 0
    if flipped:
        n = (-n[0], -n[1], -n[2])
    if mflags & (MAT_CLOSURE_NORMALS | MAT_HAIR):
        orient_closures(rows, closures, n, flipped)
    return closures, n


@inlined
def connect(state, i, p, ng, ns, toward_light, mflags, hit, rows, spectral, eta, registers, camera, settings,
            collapsed, f, scratch):
    """Connect path ``i``'s vertex ``p`` to the camera: its spectral radiance in the pixel goes to
    ``state.radiance[i]``, the visibility ray to ``origin``/``direction``/``hit_t`` (``LIGHT_CONNECTED``).
    ``hit`` = (materials, spectra, geometry, material, triangle, u, v, glass clamps): the material is
    resolved seen from the camera, as a camera path would see it."""
    ps = state.seed[i]
    sample = state.sample[i]
    pixel, lens, importance, dist = connect_to_camera(
        camera, p, sample_2d(settings.sampler, ps, sample, SLOT_CAMERA_LENS),
        sample_2d(settings.sampler, ps, sample, SLOT_CAMERA_FILTER), state.time[i])
    if pixel < 0:
        return
    to_camera = ((lens[0] - p[0]) / dist, (lens[1] - p[1]) / dist, (lens[2] - p[2]) / dist)
    cos_og = to_camera[0] * ng[0] + to_camera[1] * ng[1] + to_camera[2] * ng[2]
    cos_ig = toward_light[0] * ng[0] + toward_light[1] * ng[1] + toward_light[2] * ng[2]
    if cos_ig == 0.0:
        return
    closures, n = _resolve(hit, p, ng, ns, to_camera, cos_og < 0.0, mflags, state.wavelength[i], state.hero[i],
                           rows, spectral, eta, registers)
    tangent, bitangent = tangents(n)
    wo_l = to_local(to_camera, tangent, bitangent, n)
    wi_l = to_local(toward_light, tangent, bitangent, n)
    if not consistent(cos_og, cos_ig, wo_l[2], wi_l[2]):
        return
    bsdf_evaluate(rows, spectral, eta, closures, wo_l, wi_l, state.wavelength[i], state.hero[i], collapsed, f,
                  scratch)
    factor = abs(wi_l[2]) / abs(cos_ig) * abs(cos_og) / (dist * dist) * importance
    any_light = False
    for c in range(f.shape[0]):
        state.radiance[i, c] = state.throughput[i, c] * f[c] * factor
        any_light = any_light or state.radiance[i, c] > 0.0
    if not any_light:
        return
    origin = offset_origin(p, ng, to_camera)
    wx, wy, wz = lens[0] - origin[0], lens[1] - origin[1], lens[2] - origin[2]
    remaining = math.sqrt(wx * wx + wy * wy + wz * wz)
    if not (remaining > 0.0 and math.isfinite(remaining)):
        return
    for c in range(3):
        state.origin[i, c] = origin[c]
    state.direction[i, 0] = wx / remaining
    state.direction[i, 1] = wy / remaining
    state.direction[i, 2] = wz / remaining
    state.hit_t[i] = remaining * (1.0 - SHADOW_SHORTEN)
    state.pixel[i] = pixel
    state.flags[i] |= LIGHT_CONNECTED


@kernel
def light_bounce_kernel(state, rays, count, hit_triangle, hit_t, hit_u, hit_v, light_of_path, geometry, materials,
                        lights, spectra, camera, settings, depth, next_rays, scratch, glass_clamps, rejected):
    """One bounce of the light paths queued in ``rays``: connect or go on (see the module docstring).
    Returns the number of rays queued in ``next_rays``."""
    k = state.throughput.shape[1]
    rows, spectral, eta, weight, li, f, mix, registers, _ = scratch
    queued = 0
    for j in range(count):
        i = rays.path[j]
        triangle = hit_triangle[j]
        if triangle < 0:
            continue
        p, ng, ns = surface_at(geometry, triangle, float(hit_u[j]), float(hit_v[j]), state.time[i])
        if depth == 0:
            row = lights.rows[light_of_path[i]]
            if int(row[L_KIND]) == POINT or int(row[L_KIND]) == SPHERE:
                falloff = spot_falloff(row, p[0], p[1], p[2])
                for c in range(k):
                    state.throughput[i, c] *= falloff
        material = geometry.material[triangle]
        mflags = materials.flags[material]
        if mflags & MAT_DISPERSIVE and not state.flags[i] & COLLAPSED:
            collapse_to_hero(state, i)
        collapsed = state.flags[i] & COLLAPSED != 0
        toward_light = (-state.direction[i, 0], -state.direction[i, 1], -state.direction[i, 2])
        lam = state.wavelength[i]
        hero = state.hero[i]
        hit = (materials, spectra, geometry, material, triangle, float(hit_u[j]), float(hit_v[j]), glass_clamps)
        if not mflags & MAT_DELTA:
            if state.flags[i] & LIGHT_SPECULAR:
                connect(state, i, p, ng, ns, toward_light, mflags, hit, rows, spectral, eta, registers, camera,
                        settings, collapsed, f, mix)
            continue
        if depth >= settings.max_bounces:
            continue
        cos_in_g = toward_light[0] * ng[0] + toward_light[1] * ng[1] + toward_light[2] * ng[2]
        closures, n = _resolve(hit, p, ng, ns, toward_light, cos_in_g < 0.0, mflags, lam, hero, rows, spectral, eta,
                               registers)
        tangent, bitangent = tangents(n)
        wo_l = to_local(toward_light, tangent, bitangent, n)
        wi_l, wi, pdf, sampled, eta_scale, largest, _ = sample_scattering(state, i, depth, settings, rows, spectral,
                                                                          eta, closures, wo_l, (tangent, bitangent, n),
                                                                          collapsed, weight, mix)
        cos_out_g = wi[0] * ng[0] + wi[1] * ng[1] + wi[2] * ng[2]
        if not (largest > 0.0 and pdf > 0.0 and cos_in_g != 0.0 and wi_l[2] != 0.0
                and consistent(cos_in_g, cos_out_g, wo_l[2], wi_l[2])):
            continue
        adjoint = eta_scale * abs(wo_l[2]) * abs(cos_out_g) / (abs(cos_in_g) * abs(wi_l[2]))
        for c in range(k):
            state.throughput[i, c] *= weight[c] * adjoint
        if not survives(state, i, depth, depth, settings, collapsed):
            continue
        if not ((mflags & MAT_NULL) != 0 and wo_l[2] * wi_l[2] < 0.0):
            state.flags[i] |= LIGHT_SPECULAR
        pushed = push_ray(state, next_rays, queued, i, offset_origin(p, ng, wi), wi)
        queued += pushed
        rejected[0] += 1 - pushed
    return queued


@kernel
def queue_connections(state, count, rays):
    """Queue the visibility rays of the connected paths among rows 0 .. count-1, in path order."""
    queued = 0
    for i in range(count):
        if not state.flags[i] & LIGHT_CONNECTED:
            continue
        for c in range(3):
            rays.origin[queued, c] = state.origin[i, c]
            rays.direction[queued, c] = state.direction[i, c]
        rays.tmax[queued] = state.hit_t[i]
        rays.path[queued] = i
        queued += 1
    return queued


@kernel
def connection_splats(state, rays, count, occluded, ws, pixel, rgb):
    """The splats of the first ``count`` visibility rays that reached the camera (``occluded`` -1), in
    path order: ``pixel[m]`` and ``rgb[m]`` (scene-linear Rec.709); returns how many."""
    m = 0
    for j in range(count):
        if occluded[j] == 0:
            continue
        i = rays.path[j]
        r, g, b = radiance_to_rgb(ws, state.radiance[i], state.wavelength[i], state.wavelength_pdf[i])
        pixel[m] = state.pixel[i]
        rgb[m, 0] = r
        rgb[m, 1] = g
        rgb[m, 2] = b
        m += 1
    return m
