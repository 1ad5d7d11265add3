"""What a camera path writes for the data passes (Depth, Mist, Position, Normal, UV, Vector, Object and Material
Index, AO, AOVs) at the surfaces it meets before it scatters: Cycles' ``film_write_data_passes`` and
``integrate_surface_ao``, run while its path flags PATH_RAY_TRANSPARENT_BACKGROUND (Prism's ``CAMERA_PATH``) and
PATH_RAY_CAMERA (``CAMERA_PATH`` at bounce 0) hold.

Cycles goes on through cut-outs (a Transparent BSDF, an alpha) to the first surface whose alpha (1 - its
transparency) reaches View Layer ▸ Passes ▸ Data ▸ Alpha Threshold (any surface where the threshold is 0), so that
a leaf's cut-out shows in Normal and Depth what lies behind it:

- Normal, UV and Vector are that surface's (``PASSES_DONE`` once written);
- Depth, Position and the indices are overwritten at each surface until then (a sample that scatters off a cut-out
  below the threshold keeps the cut-out's, one that reaches the world none);
- AOVs are added at each surface until then (Cycles' AOV Output nodes write while the pass is not done);
- Mist and AO are added at every surface before the first scattering, weighted by the surface's alpha and by what
  the cut-outs before it let through (the throughput's mean): blended by alpha, as Cycles blends them.

A volume's boundary (``MAT_BOUNDARY``) writes nothing, nor does a shadow catcher's copy (``CATCHER_PASS``), as in
Cycles. The constants (mist, AO distance, the threshold) are ``PassData.first_hit_data`` (``tracer.data_passes``).
"""

from __future__ import annotations

import math

from ..data_passes import ALPHA_THRESHOLD, AO_DISTANCE, MIST_FALLOFF, MIST_INV_DEPTH, MIST_START, ORTHOGRAPHIC
from ..geometry import offset_origin
from ..jit import inlined, kernel
from ..materials.table import MAT_BOUNDARY
from ..sampler import sample_2d
from ..state import CAMERA_PATH, CATCHER_PASS, PASSES_DONE
from ..terminator import terminator_lift
from ..vec3 import tangents, to_world
from ..warps import cosine_hemisphere
from .see_through import mean_throughput

#: The sampler slot of the AO pass's direction (2-D): far past any bounce's slots.
SLOT_AO = 1 << 20


@inlined
def writes_data_passes(state, i, layout, material_flags):
    """Whether path ``i``, at a surface of a material with ``material_flags``, writes data passes there."""
    return (layout.columns > 0 and state.flags[i] & (CAMERA_PATH | CATCHER_PASS) == CAMERA_PATH
            and material_flags & MAT_BOUNDARY == 0)


@inlined
def camera_depth(passes, p):
    """The distance of ``p`` (in the render's space) along the camera's view axis (m)."""
    a, c = passes.camera_axes, passes.camera_at
    return -((p[0] - c[0]) * a[0, 2] + (p[1] - c[1]) * a[1, 2] + (p[2] - c[2]) * a[2, 2])


@inlined
def _mist(passes, p):
    """1 - mist at ``p`` (Cycles' ``film_write_data_passes``: distance from the camera, or along its axis
    for an orthographic one, mapped through start, depth and falloff)."""
    data = passes.first_hit_data
    if data[ORTHOGRAPHIC] > 0.0:
        distance = abs(camera_depth(passes, p))
    else:
        c = passes.camera_at
        distance = math.sqrt((p[0] - c[0]) ** 2 + (p[1] - c[1]) ** 2 + (p[2] - c[2]) ** 2)
    mist = min(max((distance - data[MIST_START]) * data[MIST_INV_DEPTH], 0.0), 1.0)
    falloff = data[MIST_FALLOFF]
    if falloff != 1.0:
        mist = mist ** falloff
    return 1.0 - mist


@kernel
def _raster(passes, frame, x, y, z):
    """Pixel position (x, y) of the world point (x, y, z) in the camera of ``frame`` (0 previous, 1 now, 2 next)."""
    m = passes.world_to_raster[frame]
    w = m[3, 0] * x + m[3, 1] * y + m[3, 2] * z + m[3, 3]
    w = w if w != 0.0 else 1e-30
    return ((m[0, 0] * x + m[0, 1] * y + m[0, 2] * z + m[0, 3]) / w,
            (m[1, 0] * x + m[1, 1] * y + m[1, 2] * z + m[1, 3]) / w)


@inlined
def _vector(state, passes, layout, i, p, triangle):
    """The Vector pass of the hit at ``p`` (Cycles' ``camera_motion_vector``): the surface point where it is
    at the previous and next frames (its triangle's corners moved by their displacements, same
    barycentrics), each projected by that frame's camera; previous - now, now - next, in pixels."""
    u, v = state.hit_u[i], state.hit_v[i]
    motion = passes.triangle_motion[triangle]
    x = p[0] + passes.render_origin[0]
    y = p[1] + passes.render_origin[1]
    z = p[2] + passes.render_origin[2]
    now_x, now_y = _raster(passes, 1, x, y, z)
    w = 1.0 - u - v
    pre_x, pre_y = _raster(passes, 0, x + w * motion[0, 0, 0] + u * motion[0, 1, 0] + v * motion[0, 2, 0],
                           y + w * motion[0, 0, 1] + u * motion[0, 1, 1] + v * motion[0, 2, 1],
                           z + w * motion[0, 0, 2] + u * motion[0, 1, 2] + v * motion[0, 2, 2])
    post_x, post_y = _raster(passes, 2, x + w * motion[1, 0, 0] + u * motion[1, 1, 0] + v * motion[1, 2, 0],
                             y + w * motion[1, 0, 1] + u * motion[1, 1, 1] + v * motion[1, 2, 1],
                             z + w * motion[1, 0, 2] + u * motion[1, 1, 2] + v * motion[1, 2, 2])
    passes.values[i, layout.vector] = pre_x - now_x
    passes.values[i, layout.vector + 1] = pre_y - now_y
    passes.values[i, layout.vector + 2] = now_x - post_x
    passes.values[i, layout.vector + 3] = now_y - post_y
    passes.values[i, layout.vector + 4] = 1.0


@inlined
def _queue_ao_ray(state, passes, settings, geometry, i, p, ng, ns, n, triangle, alpha):
    """This surface's ambient-occlusion ray (Cycles' ``integrate_surface_ao``: a cosine-weighted direction about
    the shading normal ``n``, as far as World ▸ Ambient Occlusion ▸ Distance, from where the shadow terminator's
    Geometry Offset lifts shadow rays: ``terminator``), weighted by the path's throughput × ``alpha``."""
    u1, u2 = sample_2d(settings.sampler, state.seed[i], state.sample[i], SLOT_AO)
    tangent, bitangent = tangents(n)
    d = to_world(cosine_hemisphere(u1, u2), tangent, bitangent, n)
    lift = terminator_lift(geometry, triangle, state.hit_u[i], state.hit_v[i], ng, ns, d, state.time[i])
    o = offset_origin((p[0] + lift[0], p[1] + lift[1], p[2] + lift[2]), ng, d)
    j = passes.ao_count[0]
    rays = passes.ao_rays
    for c in range(3):
        rays.origin[j, c] = o[c]
        rays.direction[j, c] = d[c]
    rays.tmax[j] = passes.first_hit_data[AO_DISTANCE]
    rays.path[j] = i
    passes.ao_weight[i] = mean_throughput(state, i) * alpha
    passes.ao_count[0] = j + 1


@kernel
def ao_kernel(passes, layout, count):
    """The AO pass of the first ``count`` AO rays: their path's weight where the ray was free. The queue is then
    empty for the next bounce's surfaces."""
    for j in range(count):
        if passes.ao_free[j] != 0:
            i = passes.ao_rays.path[j]
            passes.values[i, layout.ao] += passes.ao_weight[i]
    passes.ao_count[0] = 0


@inlined
def camera_surface(state, passes, layout, settings, geometry, i, p, ng, ns, n, material, triangle, regs, alpha,
                   bounce):
    """The data passes of the surface camera path ``i`` meets at ``p`` (in the render's space), before it scatters
    (``writes_data_passes``): normals ``ng``, ``ns`` (geometric, smooth; facing the camera) and ``n`` (the one the
    passes show), ``alpha`` (``see_through.surface_alpha``), ``bounce`` the path's scatterings so far (0 unless it
    went through transparent glass); ``regs`` the register file of the material's program, just run for this hit."""
    if layout.mist >= 0:
        passes.values[i, layout.mist] += _mist(passes, p) * alpha * mean_throughput(state, i)
    if layout.ao >= 0 and bounce == 0:
        _queue_ao_ray(state, passes, settings, geometry, i, p, ng, ns, n, triangle, alpha)
    if state.flags[i] & PASSES_DONE:
        return
    if state.sample[i] == 0:  # Cycles writes the indices of sample 0 only, never a blend
        if layout.object_index >= 0 and passes.object_index.shape[0] > 0:
            passes.values[i, layout.object_index] = passes.object_index[triangle]
            passes.values[i, layout.object_index + 1] = 1.0
        if layout.material_index >= 0:
            passes.values[i, layout.material_index] = passes.material_index[material]
            passes.values[i, layout.material_index + 1] = 1.0
    if layout.depth >= 0:
        passes.values[i, layout.depth] = camera_depth(passes, p)
        passes.values[i, layout.depth + 1] = 1.0
    if layout.position >= 0:
        for c in range(3):
            passes.values[i, layout.position + c] = p[c] + passes.render_origin[c]
    for a in range(layout.aovs):
        first = passes.aov_registers[material, a, 0]
        linked = passes.aov_registers[material, a, 1]  # a linked AOV Output socket: its value per hit
        for c in range(4):
            value = regs[first + c] if c < linked else passes.aov_table[material, a, c]
            passes.values[i, layout.aov + 4 * a + c] += value
    threshold = passes.first_hit_data[ALPHA_THRESHOLD]
    if threshold > 0.0 and alpha < threshold:
        return
    if layout.uv >= 0 and passes.triangle_uv.shape[0] > 0:
        u, v = state.hit_u[i], state.hit_v[i]
        corners = passes.triangle_uv[triangle]
        for c in range(3):  # u, v and A (1 where the mesh has the UV map)
            passes.values[i, layout.uv + c] = ((1.0 - u - v) * corners[0, c] + u * corners[1, c]
                                               + v * corners[2, c])
    if layout.vector >= 0 and passes.triangle_motion.shape[0] > 0:
        _vector(state, passes, layout, i, p, triangle)
    if layout.normal >= 0:
        for c in range(3):
            passes.values[i, layout.normal + c] = n[c]
    state.flags[i] |= PASSES_DONE


@inlined
def camera_escape(state, passes, layout, i):
    """Camera path ``i`` reached the world before its data passes were done: no surface's Depth, Position or
    indices (Cycles' ``film_write_data_passes_background``)."""
    if state.flags[i] & (CAMERA_PATH | CATCHER_PASS | PASSES_DONE) != CAMERA_PATH:
        return
    if layout.depth >= 0:
        passes.values[i, layout.depth] = 0.0
        passes.values[i, layout.depth + 1] = 0.0
    if layout.position >= 0:
        for c in range(3):
            passes.values[i, layout.position + c] = 0.0
    if state.sample[i] == 0:
        if layout.object_index >= 0:
            passes.values[i, layout.object_index] = 0.0
            passes.values[i, layout.object_index + 1] = 0.0
        if layout.material_index >= 0:
            passes.values[i, layout.material_index] = 0.0
            passes.values[i, layout.material_index + 1] = 0.0
