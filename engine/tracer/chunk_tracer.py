"""One chunk of a pass on the worker thread that runs it: paths ``start .. stop`` traced into that
thread's buffers, and copies of what the film adds.

    chunks = ChunkTracer()                                   # one a renderer
    result = chunks.trace(renderer, start, stop, spp, light)  # a ChunkResult

Camera paths run ``stages.trace``, light paths ``stages.light_trace``; both read ``renderer.tables``,
the renderer's camera and its ``samples_done``. Each worker thread keeps its ``state.ChunkBuffers``
from chunk to chunk, made again when the tables need other sizes.
"""

from __future__ import annotations

import threading
from typing import NamedTuple

import numpy as np

from .materials.light_path import FIELDS as LIGHT_PATH_FIELDS
from .stages.pass_writes import new_pass_data
from .state import ChunkBuffers


class ChunkResult(NamedTuple):
    """A traced chunk: one sample per camera path, or the splats of light paths."""

    pixel: np.ndarray  # [n] pixel index in the frame
    rgb: np.ndarray  # [n, 3]
    values: np.ndarray | None  # [n, C] pass values (None for light paths)
    rays: int  # rays cast
    rejected: int  # rays dropped as non-finite
    clamps: np.ndarray  # int64 [G] wavelength samples clamped at each glass's range
    spectral: tuple | None  # ``SpectralFilm.record`` of the paths (None without a spectral film or for light paths)
    alpha: np.ndarray | None  # [n] alpha when the film keeps it (None for light paths)


class ChunkTracer:
    """Traces chunks of a renderer's passes with buffers of the calling thread."""

    def __init__(self):
        self._local = threading.local()

    def _buffers(self, paths: int, tables) -> ChunkBuffers:
        buffers = getattr(self._local, "buffers", None)
        layout = tables.pass_layout.kernel
        registers = tables.material_table.register_count
        if (buffers is None or buffers.capacity < paths or buffers.k != tables.wavelengths.count
                or buffers.passes.values.shape[1] != layout.columns or buffers.passes.spectral.shape[1] != layout.slots
                or buffers.scratch.registers.shape[0] < registers + LIGHT_PATH_FIELDS):
            passes = new_pass_data(paths, tables.wavelengths.count, tables.pass_layout)
            buffers = self._local.buffers = ChunkBuffers(paths, tables.wavelengths.count, passes, registers)
        return buffers

    def trace(self, renderer, start: int, stop: int, spp: int, light: bool = False) -> ChunkResult:
        """Trace camera (or, with ``light``, light) paths ``start .. stop`` of ``renderer``'s pass of
        ``spp`` samples per pixel."""
        count = stop - start
        tables = renderer.tables
        # with a shadow catcher each camera path may split once: its copy takes a row after the chunk's paths
        rows = 2 * count if tables.kernel_settings.shadow_catcher and not light else count
        buffers = self._buffers(rows, tables)
        clamps = np.zeros(len(tables.material_table.arrays.glasses), np.int64)
        if light:
            from .stages.light_trace import light_buffers, trace_light_chunk

            extra = light_buffers(self._local, count)
            splats, rays, rejected = trace_light_chunk(renderer, buffers, extra, start, count, spp,
                                                       renderer.samples_done, clamps)
            return ChunkResult(extra.pixel[:splats].copy(), buffers.rgb[:splats].copy(), None, rays, rejected, clamps,
                               None, None)
        from .stages.trace import trace_chunk

        rays, rejected = trace_chunk(renderer, buffers, start, count, spp, renderer.samples_done, clamps)
        values = buffers.passes.values[:count].copy()
        spectral = None
        if renderer.spectral_film is not None:
            spectral = renderer.spectral_film.record(buffers.state, count)
        alpha = 1.0 - buffers.state.transparency[:count] if tables.needs_alpha else None
        return ChunkResult(buffers.state.pixel[:count].copy(), buffers.rgb[:count].copy(), values, rays, rejected,
                           clamps, spectral, alpha)
