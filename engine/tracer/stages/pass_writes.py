"""What the stages write for the render passes (``tracer.pass_table`` declares them; ``layout`` says which are on).

Per path (``PassData``): ``values`` [n, columns] (data passes and AOVs, written directly by
``data_pass_writes``), ``spectral``
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

The light split (Cycles' meaning): light that reaches the camera straight from an emitter or the world, or
through cut-outs only (``CAMERA_PATH``), is Emission or Environment; any other light is attributed to the lobes of
the surface where the path first scattered, in proportion to each lobe category's share of the BSDF in the
direction it arrived from (per wavelength), Direct when that surface was its last scattering (Cycles' bounce 1,
or light sampling at that surface), Indirect otherwise. A surface seen through cut-outs counts as the camera's, as
in Cycles. The stages do not route light by category: each bounce, ``route_emission_kernel`` (after the
emission stage) and ``route_shadows_kernel`` (after the shadow rays) split each path's radiance grown since it was
last routed (``snapshot``), with the shares recorded where the camera saw the vertex: ``split[i, 0]`` for light
sampling there (``DIRECT_SAMPLED``), ``split[i, 1]`` for the direction sampled at its first scattering. Colour =
throughput × the BSDF sample weight × share at each such surface, whose mean is each category's albedo seen
through the cut-outs before it.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..bsdf.closure import C_KIND, CONDUCTOR, DIFFUSE, SAMPLED_DELTA, SAMPLED_SUBSURFACE, SAMPLED_TRANSMISSION
from ..bsdf.dispatch import closure_evaluate
from ..data_passes import FIRST_HIT_DATA
from ..jit import inlined, kernel
from ..spectra.table import spectrum_value
from ..spectra.wavelength_sampling import radiance_to_rgb
from ..state import CAMERA_PATH, CATCHER_HIT, CATCHER_PASS, DIRECT_SAMPLED, new_ray_queue
from .bounces import path_bounce
from .data_pass_writes import camera_depth
from .see_through import mean_throughput

PassData = namedtuple("PassData", "values spectral snapshot split feature camera_axes camera_at render_origin aov_table "
                                   "aov_registers "
                                   "first_hit_data object_index material_index triangle_uv triangle_motion "
                                   "world_to_raster ao_rays ao_free ao_weight ao_count row_object "
                                   "catcher_matte catcher_background catcher_copy catcher_next")

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
            passes.snapshot[i, :] = 0.0
    passes.ao_count[0] = 0


@kernel
def deposit(passes, layout, i, k, value, group, slot, albedo):
    """Light ``value`` of wavelength column ``k`` reached path ``i``: to light group ``group`` and slot
    ``slot`` (-1: neither), and to the denoising albedo when ``albedo`` and no surface wrote it yet."""
    if group >= 0 and layout.groups > 0:
        passes.spectral[i, layout.group + group, k] += value
    if slot >= 0:
        passes.spectral[i, slot, k] += value
        if slot == layout.light + EMISSION or slot == layout.light + ENVIRONMENT:
            passes.snapshot[i, k] += value  # seen directly: attributed already (``route_*``)
    if albedo and layout.denoising_albedo >= 0 and passes.feature[i] == 0:
        passes.spectral[i, layout.denoising_albedo, k] += value


@inlined
def camera_slot(state, i, layout, escaped):
    """The slot of light path ``i`` finds while the camera still sees through it (``CAMERA_PATH``: straight
    through cut-outs, or transparent glass; Cycles' paths without PATH_RAY_ANY_PASS): Environment or Emission;
    else -1."""
    if layout.light < 0 or not state.flags[i] & CAMERA_PATH:
        return -1
    return layout.light + (ENVIRONMENT if escaped else EMISSION)


@inlined
def features_done(passes, layout, i):
    if passes.feature.shape[0] > 0:
        passes.feature[i] = 1


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
        passes.values[i, layout.denoising_depth] = camera_depth(passes, p)
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
    """Where a path the camera still sees through (``CAMERA_PATH``) scatters: the lobe shares of the sampled direction
    (delta lobes by what they did), which split the light it finds from there on, and the colour passes (throughput
    × sample weight × share, reflectance carried on a white spectrum)."""
    shares = passes.split[i, 1]
    if sampled & SAMPLED_SUBSURFACE:  # Cycles' passes count subsurface scattering as diffuse
        shares[:, :] = 0.0
        shares[DIFFUSE_SHARE, :] = 1.0
    elif sampled & SAMPLED_DELTA:
        shares[:, :] = 0.0
        shares[TRANSMISSION if sampled & SAMPLED_TRANSMISSION else GLOSSY, :] = 1.0
    else:
        lobe_shares(rows, spectral, eta, count, wo, wi, lam, hero, collapsed, scratch, shares)
    mean = mean_throughput(state, i)
    for k in range(weight.shape[0]):
        # what the cut-outs before let through; a path that keeps only its hero from here (dispersion, ×K): its
        # hero's share for every wavelength (exact behind grey cut-outs)
        seen = mean if collapsed else state.throughput[i, k]
        white = seen * weight[k] * spectrum_value(spectra, layout.white, lam[k])
        if white == white:
            for c in range(3):
                passes.spectral[i, layout.light + COLOUR + c, k] += white * shares[c, k]


@inlined
def _route(state, passes, layout, i, offset, shares):
    """Path ``i``'s radiance since it was last routed: to slot ``offset`` (``EMISSION``), or split by ``shares``
    [3, K] into the Direct or Indirect slots of the three lobe categories (``offset`` ``DIRECT`` / ``INDIRECT``)."""
    base = layout.light
    for k in range(state.radiance.shape[1]):
        now = state.radiance[i, k]
        grown = now - passes.snapshot[i, k]
        passes.snapshot[i, k] = now
        if grown == 0.0:
            continue
        if offset == EMISSION:
            passes.spectral[i, base + EMISSION, k] += grown
        else:
            for c in range(3):
                passes.spectral[i, base + offset + 2 * c, k] += grown * shares[c, k]


@inlined
def _unsplit(state, i):
    """A path split at a shadow catcher writes Combined only, as in Cycles (``stages.shadow_catcher``), and so does
    its copy."""
    return state.flags[i] & (CATCHER_HIT | CATCHER_PASS) != 0


@kernel
def route_emission_kernel(state, passes, layout, rays, count, depth):
    """Split the light that this bounce's first ``count`` rays of ``rays`` found (emitters, the world, a medium's
    emission): seen by the camera (``camera_slot`` took what it deposited; the rest is a medium's emission), after
    one scattering Direct, after more Indirect, by the shares of the first scattering's sampled direction."""
    for j in range(count):
        i = rays.path[j]
        if _unsplit(state, i):
            continue
        if state.flags[i] & CAMERA_PATH:
            _route(state, passes, layout, i, EMISSION, passes.split[i, 1])
        else:
            _route(state, passes, layout, i, DIRECT if path_bounce(state, i, depth) <= 1 else INDIRECT,
                   passes.split[i, 1])


@kernel
def route_shadows_kernel(state, passes, layout, surface, count):
    """Split the light that this bounce's light sampling brought the first ``count`` paths of ``surface``: Direct by
    the shares of the light's direction where the camera saw the vertex (``DIRECT_SAMPLED``), else Indirect."""
    for s in range(count):
        i = surface.path[s]
        if _unsplit(state, i):
            continue
        if state.flags[i] & DIRECT_SAMPLED:
            state.flags[i] &= ~DIRECT_SAMPLED
            _route(state, passes, layout, i, DIRECT, passes.split[i, 0])
        else:
            _route(state, passes, layout, i, INDIRECT, passes.split[i, 1])


@kernel
def route_end_kernel(state, passes, layout, count):
    """Whatever light of paths 0 .. count-1 no bounce routed: Indirect."""
    for i in range(count):
        if not _unsplit(state, i):
            _route(state, passes, layout, i, INDIRECT, passes.split[i, 1])


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
