"""What the stages write for the render passes (``tracer.pass_table`` declares them; ``layout`` says which are on).

Per path (``PassData``): ``values`` [n, columns] (data passes and AOVs, written directly), ``spectral``
[n, slots, K] (light, albedo and colour buffers, per wavelength, turned into Rec.709 by
``convert_kernel``), and for the light split ``snapshot`` [n, K] and ``split`` [n, 2, 3, K]; ``feature``
[n] (1 once the denoising features are written). Render constants (``Renderer.pass_data``):
``camera_axes`` [3, 3] (camera to world: right, up, back columns), ``camera_at`` [3] (the camera in the
render's space, m), ``render_origin`` [3] (world position of the render space's origin, m) and
``aov_table`` [materials, AOVs, 4] (what each material's AOV Outputs write) and ``aov_registers``
[materials, AOVs, 2] (where an AOV that varies per hit is in the material's registers, ``pass_table.aov_registers``).
With a shadow catcher (``stages.shadow_catcher``): ``catcher_matte`` / ``catcher_background`` [n, K] (a path's
radiance at its split, the world seen along its camera ray), ``catcher_copy`` int32 [n] (the row of its copy,
-1: none) and ``catcher_next`` int64 [1] (the next free row).

The light split (Cycles' meaning): light that reaches the camera straight from an emitter or the world
is Emission or Environment; any other light is attributed to the lobes of the first surface it met,
in proportion to each lobe category's share of the BSDF in the direction it arrived from (per
wavelength), Direct when that surface was its last scattering, Indirect otherwise. The stages do not
route light by category: ``route_kernel`` takes the growth of each path's radiance at three points
(after the first vertex's light sampling, after the second ray's emission, at the end) and splits it
with the shares recorded at the first vertex: ``split[i, 0]`` for light sampling, ``split[i, 1]`` for
the sampled direction. Colour = the BSDF sample weight × share, whose mean is each category's albedo.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..bsdf.closure import C_KIND, CONDUCTOR, DIFFUSE, SAMPLED_DELTA, SAMPLED_SUBSURFACE, SAMPLED_TRANSMISSION
from ..bsdf.dispatch import closure_evaluate
from ..data_passes import AO_DISTANCE, FIRST_HIT_DATA, MIST_FALLOFF, MIST_INV_DEPTH, MIST_START, ORTHOGRAPHIC
from ..geometry import offset_origin
from ..jit import inlined, kernel
from ..sampler import sample_2d
from ..spectra.table import spectrum_value
from ..spectra.wavelength_sampling import radiance_to_rgb
from ..state import CATCHER_HIT, new_ray_queue
from ..vec3 import tangents, to_world
from ..warps import cosine_hemisphere

PassData = namedtuple("PassData", "values spectral snapshot split feature camera_axes camera_at render_origin aov_table "
                                   "aov_registers "
                                   "first_hit_data object_index material_index triangle_uv triangle_motion "
                                   "world_to_raster ao_rays ao_free ao_weight ao_count row_object "
                                   "catcher_matte catcher_background catcher_copy catcher_next")

#: The sampler slot of the AO pass's direction (2-D): far past any bounce's slots.
SLOT_AO = 1 << 20

EMISSION = 0  # offsets from layout.light, in pass_table.LIGHT_SLOTS order
ENVIRONMENT = 1
DIRECT = 2  # + 2 * category
INDIRECT = 3
COLOUR = 8  # + category
DIFFUSE_SHARE = 0  # categories (the closure kind DIFFUSE is another constant)
GLOSSY = 1
TRANSMISSION = 2


def new_pass_data(n: int, k: int, film_layout) -> PassData:
    """Per-path pass storage for ``n`` paths of ``k`` wavelengths (empty arrays for what is off); the
    render constants are filled by ``Renderer.pass_data``."""
    layout = film_layout.kernel
    light = n if layout.light >= 0 else 0
    features = n if layout.denoising_albedo >= 0 or layout.denoising_normal >= 0 else 0
    ao = n if layout.ao >= 0 else 0
    catcher = n if layout.catcher >= 0 else 0
    return PassData(np.empty((n, layout.columns)), np.zeros((n, layout.slots, k)), np.zeros((light, k)),
                    np.zeros((light, 2, 3, k)), np.zeros(features, np.int8),
                    np.eye(3), np.zeros(3), np.zeros(3), np.zeros((1, len(film_layout.aov_names), 4)),
                    np.full((1, len(film_layout.aov_names), 2), -1, np.int32),
                    np.zeros(FIRST_HIT_DATA), np.zeros(0, np.float32), np.zeros(1), np.zeros((0, 3, 3), np.float32),
                    np.zeros((0, 2, 3, 3), np.float32), np.zeros((3, 4, 4)), new_ray_queue(ao), np.zeros(ao, np.int32),
                    np.zeros(ao), np.zeros(1, np.int64), np.zeros(0), np.zeros((catcher, k)), np.zeros((catcher, k)),
                    np.full(catcher, -1, np.int32), np.zeros(1, np.int64))


@kernel
def reset_kernel(passes, layout, count):
    """Paths 0 .. count-1 start with no pass data."""
    for i in range(count):
        for c in range(layout.columns):
            passes.values[i, c] = 0.0
        for s in range(layout.slots):
            passes.spectral[i, s, :] = 0.0
        if passes.feature.shape[0] > 0:
            passes.feature[i] = 0
        if passes.split.shape[0] > 0:
            passes.split[i, :, :, :] = 0.0
    passes.ao_count[0] = 0


@kernel
def deposit(passes, layout, i, k, value, group, slot, albedo):
    """Light ``value`` of wavelength column ``k`` reached path ``i``: to light group ``group`` and slot
    ``slot`` (-1: neither), and to the denoising albedo when ``albedo`` and no surface wrote it yet."""
    if group >= 0 and layout.groups > 0:
        passes.spectral[i, layout.group + group, k] += value
    if slot >= 0:
        passes.spectral[i, slot, k] += value
    if albedo and layout.denoising_albedo >= 0 and passes.feature[i] == 0:
        passes.spectral[i, layout.denoising_albedo, k] += value


@inlined
def camera_slot(layout, depth, escaped):
    """The slot of light found by the camera ray itself (Environment or Emission), else -1."""
    if depth != 0 or layout.light < 0:
        return -1
    return layout.light + (ENVIRONMENT if escaped else EMISSION)


@inlined
def features_done(passes, layout, i):
    if passes.feature.shape[0] > 0:
        passes.feature[i] = 1


@inlined
def _camera_depth(passes, p):
    a, c = passes.camera_axes, passes.camera_at
    return -((p[0] - c[0]) * a[0, 2] + (p[1] - c[1]) * a[1, 2] + (p[2] - c[2]) * a[2, 2])


@inlined
def _mist(passes, p):
    """1 - mist at ``p`` (Cycles' ``film_write_data_passes``: distance from the camera, or along its axis
    for an orthographic one, mapped through start, depth and falloff)."""
    data = passes.first_hit_data
    if data[ORTHOGRAPHIC] > 0.0:
        distance = abs(_camera_depth(passes, p))
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
def _queue_ao_ray(state, passes, settings, i, p, ng, n):
    """The first surface's ambient-occlusion ray (Cycles' ``integrate_surface_ao``: a cosine-weighted
    direction about the shading normal, as far as World ▸ Ambient Occlusion ▸ Distance)."""
    u1, u2 = sample_2d(settings.sampler, state.seed[i], state.sample[i], SLOT_AO)
    tangent, bitangent = tangents(n)
    d = to_world(cosine_hemisphere(u1, u2), tangent, bitangent, n)
    o = offset_origin(p, ng, d)
    j = passes.ao_count[0]
    rays = passes.ao_rays
    for c in range(3):
        rays.origin[j, c] = o[c]
        rays.direction[j, c] = d[c]
    rays.tmax[j] = passes.first_hit_data[AO_DISTANCE]
    rays.path[j] = i
    k = state.throughput.shape[1]
    total = 0.0
    for c in range(k):
        total += state.throughput[i, c]
    passes.ao_weight[i] = total / k
    passes.ao_count[0] = j + 1


@kernel
def ao_kernel(passes, layout, count):
    """The AO pass of the first ``count`` AO rays: their path's weight where the ray was free."""
    for j in range(count):
        if passes.ao_free[j] != 0:
            i = passes.ao_rays.path[j]
            passes.values[i, layout.ao] += passes.ao_weight[i]


@inlined
def first_hit(state, passes, layout, settings, i, p, ng, n, material, triangle, regs):
    """Depth, Mist, Position, Normal, UV, Object and Material Index, AO, Vector and AOVs of the surface the camera
    ray hit at ``p`` (in the render's space) with normals ``ng`` and ``n`` (facing the camera); ``regs`` the
    register file of the material's program, just run for this hit."""
    if layout.mist >= 0:
        passes.values[i, layout.mist] = _mist(passes, p)
    if layout.uv >= 0 and passes.triangle_uv.shape[0] > 0:
        u, v = state.hit_u[i], state.hit_v[i]
        corners = passes.triangle_uv[triangle]
        for c in range(3):  # u, v and A (1 where the mesh has the UV map)
            passes.values[i, layout.uv + c] = ((1.0 - u - v) * corners[0, c] + u * corners[1, c]
                                               + v * corners[2, c])
    if state.sample[i] == 0:  # Cycles writes the indices of sample 0 only, never a blend
        if layout.object_index >= 0 and passes.object_index.shape[0] > 0:
            passes.values[i, layout.object_index] = passes.object_index[triangle]
            passes.values[i, layout.object_index + 1] = 1.0
        if layout.material_index >= 0:
            passes.values[i, layout.material_index] = passes.material_index[material]
            passes.values[i, layout.material_index + 1] = 1.0
    if layout.ao >= 0:
        _queue_ao_ray(state, passes, settings, i, p, ng, n)
    if layout.vector >= 0 and passes.triangle_motion.shape[0] > 0:
        _vector(state, passes, layout, i, p, triangle)
    for a in range(layout.aovs):
        for c in range(4):
            passes.values[i, layout.aov + 4 * a + c] = passes.aov_table[material, a, c]
        first = passes.aov_registers[material, a, 0]
        for c in range(passes.aov_registers[material, a, 1]):  # a linked AOV Output socket
            passes.values[i, layout.aov + 4 * a + c] = regs[first + c]
    if layout.depth >= 0:
        passes.values[i, layout.depth] = _camera_depth(passes, p)
        passes.values[i, layout.depth + 1] = 1.0
    if layout.position >= 0:
        for c in range(3):
            passes.values[i, layout.position + c] = p[c] + passes.render_origin[c]
    if layout.normal >= 0:
        for c in range(3):
            passes.values[i, layout.normal + c] = n[c]


@kernel
def surface_features(state, passes, layout, i, p, n, weight, spectra):
    """Denoising features of the first surface that is not all mirror or glass: its camera-space
    normal and depth, and its albedo (the BSDF sample's weight, whose mean is the albedo) seen through
    what the path crossed before."""
    if passes.feature.shape[0] == 0 or passes.feature[i] != 0:
        return
    passes.feature[i] = 1
    if layout.denoising_normal >= 0:
        v = passes.camera_axes
        right = n[0] * v[0, 0] + n[1] * v[1, 0] + n[2] * v[2, 0]
        up = n[0] * v[0, 1] + n[1] * v[1, 1] + n[2] * v[2, 1]
        forward = -(n[0] * v[0, 2] + n[1] * v[1, 2] + n[2] * v[2, 2])
        passes.values[i, layout.denoising_normal] = right
        passes.values[i, layout.denoising_normal + 1] = up
        passes.values[i, layout.denoising_normal + 2] = forward
    if layout.denoising_depth >= 0:
        passes.values[i, layout.denoising_depth] = _camera_depth(passes, p)
        passes.values[i, layout.denoising_depth + 1] = 1.0
    if layout.denoising_albedo >= 0:
        for k in range(weight.shape[0]):
            value = state.throughput[i, k] * weight[k] * spectrum_value(spectra, layout.white, state.wavelength[i, k])
            if value == value:
                passes.spectral[i, layout.denoising_albedo, k] += value


@inlined
def _category(row, wo_z, wi_z):
    kind = int(row[C_KIND])
    if kind == DIFFUSE:
        return 0
    if kind == CONDUCTOR or wo_z * wi_z > 0.0:
        return GLOSSY
    return TRANSMISSION


@kernel
def lobe_shares(rows, spectral, eta, count, wo, wi, wavelength_nm, hero, collapsed, scratch, out):
    """``out[c, k]``: the share of lobe category c (diffuse, glossy, transmission) in the material's f
    for light arriving from ``wi`` (local frame), per wavelength column k."""
    out[:, :] = 0.0
    if count == 1:
        out[_category(rows[0], wo[2], wi[2]), :] = 1.0
        return
    for c in range(count):
        closure_evaluate(rows[c], spectral[c], eta[c], wo, wi, wavelength_nm, hero, collapsed, scratch)
        category = _category(rows[c], wo[2], wi[2])
        for k in range(out.shape[1]):
            out[category, k] += spectral[c, 2, k] * scratch[k]
    for k in range(out.shape[1]):
        total = out[0, k] + out[1, k] + out[2, k]
        for c in range(3):
            out[c, k] = out[c, k] / total if total > 0.0 else (1.0 / 3.0)


@kernel
def first_bounce(state, passes, layout, i, rows, spectral, eta, count, wo, wi, lam, hero, collapsed, sampled,
                 weight, scratch, spectra):
    """At the first surface: the lobe shares of the sampled direction (delta lobes by what they did)
    and the colour passes (sample weight × share, reflectance carried on a white spectrum)."""
    shares = passes.split[i, 1]
    if sampled & SAMPLED_SUBSURFACE:  # Cycles' passes count subsurface scattering as diffuse
        shares[:, :] = 0.0
        shares[DIFFUSE_SHARE, :] = 1.0
    elif sampled & SAMPLED_DELTA:
        shares[:, :] = 0.0
        shares[TRANSMISSION if sampled & SAMPLED_TRANSMISSION else GLOSSY, :] = 1.0
    else:
        lobe_shares(rows, spectral, eta, count, wo, wi, lam, hero, collapsed, scratch, shares)
    for k in range(weight.shape[0]):
        white = weight[k] * spectrum_value(spectra, layout.white, lam[k])
        if white == white:
            for c in range(3):
                passes.spectral[i, layout.light + COLOUR + c, k] += white * shares[c, k]


@kernel
def route_kernel(state, passes, layout, count, step):
    """Split each path's new radiance since the last step: ``step`` 0 after the first vertex's light
    sampling (Direct, shares of the light's direction), 1 after the second ray's emission (Direct,
    shares of the sampled direction), 2 at the end (Indirect)."""
    k_count = state.radiance.shape[1]
    base = layout.light
    for i in range(count):
        if state.flags[i] & CATCHER_HIT:
            continue  # a path split at a shadow catcher writes Combined only, as in Cycles (``stages.shadow_catcher``)
        for k in range(k_count):
            now = state.radiance[i, k]
            if step == 0:
                before = passes.spectral[i, base + EMISSION, k] + passes.spectral[i, base + ENVIRONMENT, k]
            else:
                before = passes.snapshot[i, k]
            passes.snapshot[i, k] = now
            grown = now - before
            if grown == 0.0:
                continue
            shares = passes.split[i, 0] if step == 0 else passes.split[i, 1]
            offset = INDIRECT if step == 2 else DIRECT
            for c in range(3):
                passes.spectral[i, base + offset + 2 * c, k] += grown * shares[c, k]


@kernel
def convert_kernel(state, passes, layout, ws, count):
    """Each spectral slot of paths 0 .. count-1 as Rec.709 in its three value columns."""
    for i in range(count):
        for s in range(layout.slots):
            r, g, b = radiance_to_rgb(ws, passes.spectral[i, s], state.wavelength[i], state.wavelength_pdf[i])
            column = layout.rgb_column + 3 * s
            passes.values[i, column] = r
            passes.values[i, column + 1] = g
            passes.values[i, column + 2] = b
