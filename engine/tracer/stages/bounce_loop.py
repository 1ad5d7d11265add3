"""A chunk's whole bounce loop in one compiled call: Embree queries and the stage kernels in turn.

    rays_cast = bounce_loop_kernel(loop, arrays, caster, camera, passes, layout, count, queued, glass_clamps,
                                   see_through, route_light)

After the camera stage has queued the chunk's first rays, everything up to the film runs here without
the GIL: closest hits (Embree, called from compiled code), emission, shading with light and BSDF
sampling, shadow rays (film layers, then occlusion), the light split of the render passes, and the
radiance → Rec.709 conversion. The stages are the same kernels ``stages.trace`` used to call from
Python between Embree queries (a wavefront inside one call): the queues keep paths in order, so the
image is the one the Python loop made, bit for bit, and the kernels stay small and testable alone.

Records (named tuples, built once and kept, so calls from Python are typed cheaply):
``state.LoopBuffers`` a thread's working memory, ``SceneArrays`` the render's tables, and
``embree.queries.RayCaster`` the Embree scene with this thread's ray record.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..camera_clip import clip_far_hits_kernel
from ..embree.queries import closest_hits, occlusion
from ..jit import inlined, kernel
from ..state import LoopBuffers  # noqa: F401  (the loop's record, declared with the buffers)
from .bounces import step_limit
from .emission import emission_kernel
from .film import film_kernel
from .data_pass_writes import ao_kernel
from .pass_writes import convert_kernel, route_emission_kernel, route_end_kernel, route_shadows_kernel
from .shade import shade_kernel
from .shadow import film_layer_kernel, shadow_kernel, shadow_layers

#: The render's tables the loop reads (``scene_tables.SceneTables.arrays``).
SceneArrays = namedtuple("SceneArrays", "geometry materials lights spectra settings wavelengths")

# Inlined: a kernel called from a kernel has its code linked into the caller and optimised and compiled
# again there (numba links LLVM modules), so a middle layer of kernels would compile its callees a third time.
@inlined
def _trace_shadows(loop, arrays, caster, passes, layout, count, see_through):
    """Deliver the light of the first ``count`` shadow rays that reach their lights; returns rays cast."""
    shadows = loop.shadows
    hits = loop.hits
    rays = 0
    if see_through:
        for layer in range(shadow_layers(arrays.settings.transparent_max_bounces)):
            if count == 0:
                return rays
            closest_hits(caster, shadows.rays, count, True, hits)
            rays += count
            count = film_layer_kernel(loop.state, shadows, count, hits.triangle, hits.t, hits.u, hits.v,
                                      arrays.geometry, arrays.materials, passes, layout, arrays.spectra, loop.scratch,
                                      arrays.lights, layer)
    if count:
        occlusion(caster, shadows.rays, count, loop.occluded)
        rays += count
        shadow_kernel(loop.state, shadows, count, loop.occluded, passes, layout)
    return rays


@kernel
def bounce_loop_kernel(loop, arrays, caster, camera, passes, layout, count, queued, glass_clamps, see_through,
                       route_light):
    """Trace the ``count`` paths whose first ``queued`` rays are in ``loop.rays[0]`` until all have ended,
    then write their colours to ``loop.rgb`` (and the passes' Rec.709 columns). ``camera``: the
    ``stages.camera.CameraData`` whose Clip End ends the camera rays (``camera_clip``). ``route_light``: the
    passes split the light (``layout.light >= 0``); ``see_through``: shadow rays may cross films or
    cut-outs. Returns the rays cast."""
    state = loop.state
    settings = arrays.settings
    rays_cast = 0
    for depth in range(step_limit(settings.max_bounces, settings.transparent_max_bounces)):
        if queued == 0:
            break
        current = loop.rays[depth % 2]
        closest_hits(caster, current, queued, False, loop.hits)
        if depth == 0:
            clip_far_hits_kernel(camera, current, queued, loop.hits)
        rays_cast += queued
        surfaces = emission_kernel(state, current, queued, loop.hits.triangle, loop.hits.t, loop.hits.u, loop.hits.v,
                                   arrays.geometry, arrays.materials, arrays.lights, arrays.spectra, settings, depth,
                                   loop.surface, passes, layout, loop.scratch, caster)
        if route_light:
            route_emission_kernel(state, passes, layout, current, queued, depth)
        if surfaces == 0:
            break
        following = loop.rays[(depth + 1) % 2]
        queued, shadowed = shade_kernel(state, loop.surface, surfaces, arrays.geometry, arrays.materials,
                                        arrays.lights, arrays.spectra, settings, depth, following, loop.shadows,
                                        loop.scratch, glass_clamps, loop.rejected, passes, layout, caster)
        if shadowed:
            rays_cast += _trace_shadows(loop, arrays, caster, passes, layout, shadowed, see_through)
        if route_light:
            route_shadows_kernel(state, passes, layout, loop.surface, surfaces)
        if layout.ao >= 0 and passes.ao_count[0] > 0:  # the AO pass's rays (cut-outs: at each surface behind)
            occlusion(caster, passes.ao_rays, passes.ao_count[0], passes.ao_free)
            rays_cast += passes.ao_count[0]
            ao_kernel(passes, layout, passes.ao_count[0])
    if route_light:
        route_end_kernel(state, passes, layout, count)
    film_kernel(state, count, arrays.wavelengths, loop.rgb)
    if layout.slots:
        convert_kernel(state, passes, layout, arrays.wavelengths, count)
    return rays_cast
