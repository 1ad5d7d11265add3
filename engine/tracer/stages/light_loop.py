"""A chunk of light paths in one compiled call: emission, bounces with Embree queries, connections to
the camera and their splats (the light-tracing twin of ``stages.bounce_loop``).

    splats, rays_cast = light_loop_kernel(loop, light, arrays, caster, targets, camera, first, count,
                                          samples_per_pixel, first_sample, glass_clamps)

The same ``light_paths`` kernels in the same order as the Python loop they replace, so the splats are
the same, in the same (path) order.
"""

from __future__ import annotations

from ..embree.queries import closest_hits, occlusion
from ..jit import kernel
from .light_paths import connection_splats, emit_kernel, light_bounce_kernel, queue_connections


@kernel
def light_loop_kernel(loop, light, arrays, caster, targets, camera, first, count, samples_per_pixel, first_sample,
                      glass_clamps):
    """Trace light paths ``first .. first + count`` of the pass (``loop``: ``state.LoopBuffers``;
    ``light``: ``light_trace.LightBuffers``; ``arrays``: ``bounce_loop.SceneArrays``; ``targets``: the
    caustic targets; ``camera``: ``stages.camera.CameraData``). Returns (splats, rays cast):
    ``light.pixel[:splats]`` and ``loop.rgb[:splats]`` hold the splats."""
    state = loop.state
    settings = arrays.settings
    queued = emit_kernel(state, loop.rays[0], light.light, arrays.lights, arrays.materials, arrays.spectra,
                         arrays.geometry, targets, arrays.wavelengths, settings, first, count, samples_per_pixel,
                         first_sample, loop.scratch, camera.shutter_times)
    rays_cast = 0
    for depth in range(settings.max_bounces + 1):
        if queued == 0:
            break
        current = loop.rays[depth % 2]
        closest_hits(caster, current, queued, False, loop.hits)
        rays_cast += queued
        queued = light_bounce_kernel(state, current, queued, loop.hits.triangle, loop.hits.t, loop.hits.u,
                                     loop.hits.v, light.light, arrays.geometry, arrays.materials, arrays.lights,
                                     arrays.spectra, camera, settings, depth, loop.rays[(depth + 1) % 2],
                                     loop.scratch, glass_clamps, loop.rejected)
    connections = loop.shadows.rays
    waiting = queue_connections(state, count, connections)
    occlusion(caster, connections, waiting, loop.occluded)
    rays_cast += waiting
    splats = connection_splats(state, connections, waiting, loop.occluded, arrays.wavelengths, light.pixel, loop.rgb)
    return splats, rays_cast
