"""One chunk of light paths, bounce by bounce (``light_paths`` kernels, Embree in between), and its splats.

Like ``trace.py`` for camera paths: Python only calls kernels and Embree on whole queues. A chunk's
splats come back in path order, and the renderer adds chunks to the film in chunk order, so every
pixel sums its light-traced samples in the pass's path order whatever the chunking or thread count.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..jit import Launch
from . import light_paths as _light_paths

# Called per bounce of every light chunk (``jit.Launch``: no per-call typing of the tables).
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
    state = buffers.state
    tables = renderer.tables
    settings = tables.kernel_settings
    materials = tables.material_table.arrays
    lights = tables.light_table.arrays
    rejected = buffers.counters
    rejected[0] = 0
    current = buffers.rays[0]
    queued = emit_kernel(state, current, extra.light, lights, materials, tables.spectra, tables.geometry,
                         tables.caustic_targets, tables.wavelengths, settings, first, count, samples_per_pixel,
                         first_sample, buffers.scratch)
    rays_cast = 0
    for depth in range(settings.max_bounces + 1):
        if queued == 0:
            break
        hit = tables.accel.intersect(current, queued)
        rays_cast += queued
        following = buffers.rays[1] if current is buffers.rays[0] else buffers.rays[0]
        queued = light_bounce_kernel(state, current, queued, *hit, extra.light, tables.geometry, materials, lights,
                                     tables.spectra, renderer.camera.data, settings, depth, following,
                                     buffers.scratch, glass_clamps, rejected)
        current = following
    connections = buffers.shadows.rays
    waiting = queue_connections(state, count, connections)
    occluded = tables.accel.occluded(connections, waiting)
    rays_cast += waiting
    splats = connection_splats(state, connections, waiting, occluded, tables.wavelengths, extra.pixel, buffers.rgb)
    return splats, rays_cast, int(rejected[0])
