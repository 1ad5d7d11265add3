"""Stage 4: light that reached its vertex. A shadow ray that Embree finds free adds its contribution.

Free-standing films (``MAT_NULL``) transmit undeviated, so light behind them reaches a point along the
straight shadow ray, attenuated by T = 1 - R(λ, θ) per wavelength; cut-outs (``MAT_TRANSPARENT``: alpha,
Transparent BSDF) let it through by their transparency at the point crossed. In scenes with either,
shadow rays are traced as closest-hit queries layer by layer (``film_layer_kernel`` keeps the rays that
crossed such a surface, attenuated and moved past it; anything else blocks), up to ``shadow_layers``;
one occlusion query settles the rest. As in Cycles, a shadow ray crosses at most Transparent Max Bounces less
the transparent bounces its path made (``ShadowQueue.crossable``): the next cut-out or film blocks it.
With media (``KernelSettings.has_media``) shadow rays are always traced layer by layer: each stretch inside a
medium attenuates them by its transmittance exp(-σ_t(λ) d) (analytic in a homogeneous medium, estimated by ratio
tracking in a grid medium: ``media.transmittance``), and crossing a volume's null boundary changes their medium.
With shadow linking (``light_linking``) they are traced layer by layer too: an object outside the blocker
sets of the ray's light (``ShadowQueue.blockers``) is passed through untouched, as Cycles skips it.
"""

from __future__ import annotations

import math

from ..bsdf.thin_film import film_reflectance
from ..geometry import offset_origin, surface_at
from ..jit import inlined, kernel
from ..light_linking import blocks
from ..materials.light_path import shadow_ray
from ..materials.surface import surface_transparency
from ..materials.table import MAT_BOUNDARY, MAT_MEDIUM, MAT_NULL, MAT_TRANSPARENT
from ..media.boundary import side_medium
from ..media.transmittance import transmit
from .pass_writes import deposit

OTHER_LAYERS = 8  # layers beyond the cut-outs and films: volume boundaries, objects a light's shadow links pass


@kernel
def shadow_layers(transparent_max_bounces):
    """Layers a shadow ray is traced through before one occlusion query settles it: the Transparent Max Bounces
    cut-outs and films Cycles' shadow rays may cross, and ``OTHER_LAYERS`` more for what is no transparent bounce
    (volume boundaries, which Cycles does not count; objects outside the light's blocker sets)."""
    return transparent_max_bounces + OTHER_LAYERS


@inlined
def _cut_out(materials, spectra, geometry, material, triangle, u, v, p, ng, ns, d, wavelength_nm, scratch, out):
    """Transparency of a cut-out crossed by a shadow ray along ``d``."""
    wo = (-d[0], -d[1], -d[2])
    backfacing = wo[0] * ng[0] + wo[1] * ng[1] + wo[2] * ng[2] < 0.0
    if backfacing:
        ng = (-ng[0], -ng[1], -ng[2])
        ns = (-ns[0], -ns[1], -ns[2])
    surface_transparency(materials, spectra, geometry, material, triangle, u, v, p, ng, ns, wo, backfacing,
                         wavelength_nm, scratch.rows, scratch.registers, out, scratch.f)


@kernel
def shadow_kernel(state, shadows, count, occluded, passes, layout):
    """Add the contribution of every queued shadow ray whose occlusion result is -1 (nothing in the way)."""
    for j in range(count):
        if occluded[j] != 0:
            i = shadows.rays.path[j]
            for k in range(state.radiance.shape[1]):
                state.radiance[i, k] += shadows.contribution[j, k]
                if layout.groups > 0:
                    deposit(passes, layout, i, k, shadows.contribution[j, k], shadows.group[j], -1, False)


@kernel
def film_layer_kernel(state, shadows, count, hit_triangle, hit_t, hit_u, hit_v, geometry, materials, passes, layout,
                      spectra, scratch, lights, layer):
    """One layer of closest hits (before each ray's ``tmax``): rays that hit nothing deliver their
    contribution; rays that hit a film or a cut-out are attenuated, moved past it and kept (compacted to
    the front), as are rays that hit an object which does not block their light (shadow linking); others
    are blocked. Returns the number kept. ``passes`` / ``layout``: see ``stages.pass_writes``; ``scratch``
    is a ``state.ShadingScratch``; ``lights`` the ``LightArrays`` (their ``links``); ``layer`` how many layers
    the rays crossed before (the Light Path node's Transparent Depth of a shadow ray)."""
    kept = 0
    for j in range(count):
        i = shadows.rays.path[j]
        triangle = hit_triangle[j]
        medium = shadows.medium[j]
        if medium >= 0:  # the stretch to the hit (or to the light) lies in a medium
            o = (shadows.origin[j, 0], shadows.origin[j, 1], shadows.origin[j, 2])
            transmit(materials.media, spectra, medium, state.wavelength[i], o,
                     (shadows.direction[j, 0], shadows.direction[j, 1], shadows.direction[j, 2]),
                     float(hit_t[j]) if triangle >= 0 else shadows.distance[j], shadows.contribution[j], scratch.mix[0],
                     state.seed[i], state.sample[i], layer)
        if triangle < 0:
            for k in range(state.radiance.shape[1]):
                state.radiance[i, k] += shadows.contribution[j, k]
                if layout.groups > 0:
                    deposit(passes, layout, i, k, shadows.contribution[j, k], shadows.group[j], -1, False)
            continue
        material = geometry.material[triangle]
        mflags = materials.flags[material]
        blocker = blocks(lights, shadows.blockers[j], triangle)
        if blocker and not mflags & (MAT_NULL | MAT_TRANSPARENT):
            continue
        crossable = shadows.crossable[j]
        if blocker and not mflags & MAT_BOUNDARY:  # a transparent bounce: one more than allowed blocks the ray
            if crossable <= 0:
                continue
            crossable -= 1
        d = (shadows.direction[j, 0], shadows.direction[j, 1], shadows.direction[j, 2])
        u, v = float(hit_u[j]), float(hit_v[j])
        p, ng, ns = surface_at(geometry, triangle, u, v, state.time[i])
        if mflags & MAT_MEDIUM:  # a volume's boundary: the ray enters (against ng) or leaves its medium
            medium = side_medium(materials, material, d, ng, medium)
        if not blocker:  # shadow linking: this object casts no shadow from the ray's light
            for k in range(state.radiance.shape[1]):
                shadows.contribution[kept, k] = shadows.contribution[j, k]
        elif mflags & MAT_NULL:
            row = materials.closures[materials.closure_start[material]]
            cos = min(abs(d[0] * ng[0] + d[1] * ng[1] + d[2] * ng[2]), 1.0)
            for k in range(state.radiance.shape[1]):
                shadows.contribution[kept, k] = shadows.contribution[j, k] * (
                    1.0 - min(max(film_reflectance(row, cos, state.wavelength[i, k]), 0.0), 1.0))
        else:
            transparency = scratch.weight
            shadow_ray(scratch.registers, state, i, layer, float(hit_t[j]))
            _cut_out(materials, spectra, geometry, material, triangle, u, v, p, ng, ns, d, state.wavelength[i],
                     scratch, transparency)
            largest = 0.0
            for k in range(state.radiance.shape[1]):
                largest = max(largest, transparency[k])
            if not largest > 0.0:
                continue
            for k in range(state.radiance.shape[1]):
                shadows.contribution[kept, k] = shadows.contribution[j, k] * transparency[k]
        origin = offset_origin(p, ng, d)
        travelled = math.sqrt((origin[0] - shadows.origin[j, 0]) ** 2 + (origin[1] - shadows.origin[j, 1]) ** 2
                              + (origin[2] - shadows.origin[j, 2]) ** 2)
        remaining = shadows.distance[j] - travelled
        if not remaining > 0.0:
            remaining = 1e-9
        for c in range(3):
            shadows.origin[kept, c] = origin[c]
            shadows.direction[kept, c] = d[c]
            shadows.rays.origin[kept, c] = origin[c]
            shadows.rays.direction[kept, c] = d[c]
        shadows.distance[kept] = remaining
        shadows.rays.tmax[kept] = remaining
        shadows.rays.path[kept] = i
        shadows.group[kept] = shadows.group[j]
        shadows.medium[kept] = medium
        shadows.blockers[kept] = shadows.blockers[j]
        shadows.crossable[kept] = crossable
        kept += 1
    return kept
