"""One chunk of light paths and its splats: ``stages.light_loop`` traces it in one compiled call (or,
where the Embree queries must be seen from Python, stepwise: ``Accel.compiled_loops``).

A chunk's splats come back in path order, and the renderer adds chunks to the film in chunk order, so every
pixel sums its light-traced samples in the pass's path order whatever the chunking or thread count.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..jit import Launch
from . import light_loop as _light_loop
from . import light_paths as _light_paths

# Called once per light chunk, or per bounce stepwise (``jit.Launch``: no per-call typing of the tables).
light_loop_kernel = Launch(_light_loop.light_loop_kernel)
emit_kernel = Launch(_light_paths.emit_kernel)
light_bounce_kernel = Launch(_light_paths.light_bounce_kernel)
queue_connections = Launch(_light_paths.queue_connections)
connection_splats = Launch(_light_paths.connection_splats)

#: Per-thread memory of light chunks besides the ``ChunkBuffers``: the light of each path (int32 [n])
#: and the pixels of the chunk's splats (int64 [n]; their colours go to ``ChunkBuffers.rgb``).
LightBuffers = namedtuple("LightBuffers", "light pixel")


def light_buffers(local, n: int) -> LightBuffers:
    """The calling thread's ``LightBuffers`` for ``n`` paths (kept on ``local``, a ``threading.local``)."""
    buffers = getattr(local, "light_buffers", None)
    if buffers is None or len(buffers.light) < n:
        buffers = local.light_buffers = LightBuffers(np.empty(n, np.int32), np.empty(n, np.int64))
    return buffers


def trace_light_chunk(renderer, buffers, extra, first, count, samples_per_pixel, first_sample, glass_clamps):
    """Trace light paths ``first .. first + count`` of the pass; returns (splats, rays cast, rays dropped
    as non-finite): ``extra.pixel[:splats]`` and ``buffers.rgb[:splats]`` hold the splats."""
    tables = renderer.tables
    rejected = buffers.counters
    rejected[0] = 0
    accel = tables.accel  # held until the call returns: it owns the Embree scene the loop traces
    if not accel.compiled_loops:
        splats, rays_cast = _trace_stepwise(renderer, buffers, extra, first, count, samples_per_pixel, first_sample,
                                            glass_clamps)
    else:
        splats, rays_cast = light_loop_kernel(buffers.loop, extra, tables.arrays, accel.caster(),
                                              tables.caustic_targets, renderer.camera.data, first, count,
                                              samples_per_pixel, first_sample, glass_clamps)
    return splats, rays_cast, int(rejected[0])


def _trace_stepwise(renderer, buffers, extra, first, count, samples_per_pixel, first_sample, glass_clamps):
    """``light_loop_kernel``'s work with each Embree query made from Python through ``tables.accel``
    (so a benchmark can record the queries); the same splats."""
    state = buffers.state
    tables = renderer.tables
    settings = tables.kernel_settings
    materials = tables.material_table.arrays
    lights = tables.light_table.arrays
    current = buffers.rays[0]
    queued = emit_kernel(state, current, extra.light, lights, materials, tables.spectra, tables.geometry,
                         tables.caustic_targets, tables.wavelengths, settings, first, count, samples_per_pixel,
                         first_sample, buffers.scratch, renderer.camera.data.shutter_times)
    rays_cast = 0
    for depth in range(settings.max_bounces + 1):
        if queued == 0:
            break
        hit = tables.accel.intersect(current, queued)
        rays_cast += queued
        following = buffers.rays[1] if current is buffers.rays[0] else buffers.rays[0]
        queued = light_bounce_kernel(state, current, queued, *hit, extra.light, tables.geometry, materials, lights,
                                     tables.spectra, renderer.camera.data, settings, depth, following,
                                     buffers.scratch, glass_clamps, buffers.counters)
        current = following
    connections = buffers.shadows.rays
    waiting = queue_connections(state, count, connections)
    occluded = tables.accel.occluded(connections, waiting)
    rays_cast += waiting
    splats = connection_splats(state, connections, waiting, occluded, tables.wavelengths, extra.pixel, buffers.rgb)
    return splats, rays_cast
