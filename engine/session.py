"""One F12 or batch render: export, progressive passes, Render Result updates.

Imported only when a render starts (it pulls in the tracer: numpy, embreex,
colour-science). The session reads optional overrides from ``request`` (set by
the batch script before it starts a render) and leaves ``last_error`` and, when
asked, ``last_film`` for it.
"""

from __future__ import annotations

import math
import sys
import time
import traceback
from dataclasses import dataclass

import numpy as np

from . import kernel_cache

kernel_cache.configure()  # before anything below imports a tracer kernel module

from .export import export_scene  # noqa: E402
from .export.settings import export_settings  # noqa: E402
from .render_engine import enabled_passes  # noqa: E402
from .tracer.errors import PrismInputError  # noqa: E402


@dataclass
class RenderRequest:
    """Overrides for the next render (batch): ``None`` keeps the scene's setting.

    ``sample_offset``: start at this sample of the seed's sequence (chunked
    renders). ``quick_first_pass``: show a 1-sample pass first (interactive
    renders; changes the random sequence, so batch renders turn it off).
    ``keep_film``: leave the float64 mean in ``last_film``. ``progress_stream``:
    where to print one progress line per pass (e.g. ``sys.stderr``).
    """

    samples: int | None = None
    seed: int | None = None
    threads: int | None = None
    sample_offset: int = 0
    quick_first_pass: bool = True
    keep_film: bool = False
    progress_stream: object = None


@dataclass
class FilmSnapshot:
    """The float64 mean [H, W, 3] (row 0 = top) of a finished render and its samples."""

    mean: np.ndarray
    samples: int
    sample_offset: int
    seed: int


#: Overrides for the next render (the batch script sets it; None = the scene's settings).
request: RenderRequest | None = None
#: The message of the last render that failed, for the batch script (None if it succeeded).
last_error: str | None = None
#: Set after a render when ``request.keep_film``.
last_film: FilmSnapshot | None = None
#: Warnings of the last render (inputs Prism ignored), for tests and the batch script.
last_warnings: list[str] = []
#: The stats line of the last pass of the last render (strategy, rays/s, warnings).
last_stats: str = ""


class _Cancelled(Exception):
    """Esc pressed while a pass was running."""


def render_border(scene, width: int, height: int) -> tuple[int, int, int, int] | None:
    """The render border as pixels (x0, y0, x1, y1), rows from the TOP, half-open; None if off.

    Blender truncates border fractions times the resolution in float32; so do we,
    so the region matches the Render Result Blender allocates.
    """
    render = scene.render
    if not render.use_border:
        return None
    f32 = np.float32
    x0 = int(f32(render.border_min_x) * f32(width))
    x1 = int(f32(render.border_max_x) * f32(width))
    y0_bottom = int(f32(render.border_min_y) * f32(height))
    y1_bottom = int(f32(render.border_max_y) * f32(height))
    if (x0, y0_bottom, x1, y1_bottom) == (0, 0, width, height):
        return None
    if x1 <= x0 or y1_bottom <= y0_bottom:
        raise PrismInputError(
            f"Scene '{scene.name}': the render border is empty: draw a larger border (Ctrl+B) or turn it off."
        )
    return (x0, height - y1_bottom, x1, height - y0_bottom)


class RenderSession:
    """Renders one frame of ``depsgraph`` through ``engine`` (a ``PrismRenderEngine``)."""

    def __init__(self, engine, depsgraph, render_request: RenderRequest | None = None):
        self.engine = engine
        self.depsgraph = depsgraph
        self.request = render_request or request or RenderRequest()
        self.cancelled = False

    def fail(self, message: str) -> None:
        global last_error
        last_error = message
        self.engine.error_set(message)
        self.engine.report({"ERROR"}, message)
        self._print(f"Prism: error: {message}")

    def _print(self, line: str) -> None:
        stream = self.request.progress_stream
        if stream is not None:
            print(line, file=stream, flush=True)

    def run(self) -> None:
        global last_error, last_film, last_stats
        last_error = None
        last_film = None
        last_stats = ""
        try:
            self._render()
        except PrismInputError as error:
            self.fail(str(error))
        except MemoryError:
            self.fail("Prism ran out of memory: lower the resolution, the samples per pass or the thread count.")
        except Exception as error:  # noqa: BLE001 - a bug: one clear line in the report, details in the console
            traceback.print_exc()
            self.fail(f"Prism failed unexpectedly ({type(error).__name__}: {error}); details are in the console.")

    def _render(self) -> None:
        global last_film, last_warnings
        from .tracer.renderer import Renderer

        engine = self.engine
        scene = self.depsgraph.scene
        req = self.request
        compiling = kernel_cache.compiling_notice()
        notice = f" | {compiling}" if compiling else ""
        if compiling:
            self._print(f"Prism: {compiling}")
        engine.update_stats("", f"Prism | Exporting scene{notice}")
        warnings: list[str] = []
        tracer_scene = export_scene(self.depsgraph, warnings)
        width, height = tracer_scene.camera.resolution
        border = render_border(scene, width, height)
        settings = export_settings(
            scene, samples=req.samples, seed=req.seed, threads=req.threads, preview=engine.is_preview, border=border
        )
        last_warnings = warnings
        for message in warnings:
            engine.report({"WARNING"}, message)
            self._print(f"Prism: warning: {message}")
        engine.update_stats("", f"Prism | Preparing (BVH, spectra){notice}")
        target = settings.samples
        with Renderer(tracer_scene, settings) as renderer:
            if req.sample_offset:
                renderer.start_at_sample(req.sample_offset)
            try:
                self._passes(renderer, border, width, height, target, warnings)
            finally:
                if self.cancelled:
                    renderer.cancel()  # drop queued chunks: Esc returns within a chunk's time
            if compiling and not self.cancelled:
                kernel_cache.mark_compiled()
            if req.keep_film and not self.cancelled:
                last_film = FilmSnapshot(
                    mean=renderer.film.mean(),
                    samples=renderer.samples_done - req.sample_offset,
                    sample_offset=req.sample_offset,
                    seed=settings.seed,
                )

    def _passes(self, renderer, border, width, height, target, warnings) -> None:
        global last_stats
        engine = self.engine
        req = self.request
        x0, y0, x1, y1 = border or (0, 0, width, height)
        for name, channels, ids, _ in enabled_passes(self.depsgraph.scene):
            engine.add_pass(name, channels, ids)
        layer = self.depsgraph.view_layer.name
        result = engine.begin_result(0, 0, x1 - x0, y1 - y0, layer=layer)
        wanted = {name for name, *_ in enabled_passes(self.depsgraph.scene)}
        settings = renderer.settings
        per_pass = settings.samples_per_pass
        start_done = renderer.samples_done
        end = start_done + target
        started = time.perf_counter()
        pass_index = 0
        quick = req.quick_first_pass and per_pass > 1
        try:
            while renderer.samples_done < end:
                if engine.test_break():
                    self.cancelled = True
                    break
                done_before = renderer.samples_done - start_done

                def progress(fraction, done_before=done_before):
                    engine.update_progress(min(1.0, (done_before + fraction * per_pass) / target))
                    if engine.test_break():
                        renderer.cancel()
                        raise _Cancelled

                renderer.progress = progress
                if quick and pass_index == 0:
                    settings.samples_per_pass = 1
                try:
                    renderer.render_pass()
                except _Cancelled:
                    self.cancelled = True
                finally:
                    settings.samples_per_pass = per_pass
                pass_index += 1
                self._write(result, renderer, (x0, y0, x1, y1), wanted)
                engine.update_result(result)
                done = renderer.samples_done - start_done
                engine.update_progress(min(1.0, done / target))
                line = stats_line(renderer, pass_index, done, target, time.perf_counter() - started, warnings)
                engine.update_stats("", line)
                last_stats = line
                self._print(line)
                if self.cancelled:
                    break
        finally:
            engine.end_result(result)
        if self.cancelled:
            engine.update_stats("", f"Prism | Cancelled at {renderer.samples_done - start_done}/{target} spp")
            self._print("Prism: cancelled")

    @staticmethod
    def _write(result, renderer, box, wanted) -> None:
        x0, y0, x1, y1 = box
        passes = result.layers[0].passes
        passes["Combined"].rect = bottom_up(renderer.image_rgb()[y0:y1, x0:x1], alpha=True)
        if "Noise" in wanted:
            passes["Noise"].rect = bottom_up(renderer.variance_rgb()[y0:y1, x0:x1])
        if "Sample Count" in wanted:
            counts = renderer.film.counts[y0:y1, x0:x1].astype(np.float32)[..., None]
            passes["Sample Count"].rect = bottom_up(counts)


def bottom_up(image: np.ndarray, alpha: bool = False) -> np.ndarray:
    """[H, W, C] with row 0 at the top → Blender's flat [H*W, C(+1)], first row at the bottom."""
    height, width, channels = image.shape
    if alpha:
        rgba = np.ones((height, width, channels + 1), np.float32)
        rgba[..., :channels] = image
        image = rgba
    return np.ascontiguousarray(image[::-1], dtype=np.float32).reshape(height * width, -1)


def stats_line(renderer, pass_index: int, done: int, target: int, seconds: float, warnings) -> str:
    """``Prism | Pass 3 | 12/64 spp | 1.30 M rays/s | <strategy> | ...`` for Blender's status bar."""
    stats = renderer.stats
    rays_per_second = stats.get("rays_cast", 0) / seconds if seconds > 0 else 0.0
    parts = [
        f"Prism | Pass {pass_index} | {done}/{target} spp",
        f"{rays_per_second / 1e6:.2f} M rays/s",
        renderer.strategy,
    ]
    if stats.get("nan_samples"):
        parts.append(f"{stats['nan_samples']} NaN samples dropped")
    notes = list(warnings) + list(stats.get("warnings") or [])
    if notes:
        parts.append(f"{len(notes)} warning(s): {notes[0]}")
    return " | ".join(parts)
