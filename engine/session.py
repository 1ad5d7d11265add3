"""One F12 or batch render: export, progressive passes, Render Result updates.

Imported only when a render starts (it pulls in the tracer: numpy, embreex,
colour-science). A batch script hands its overrides over with
``engine.render_request.render_request`` and reads the ``RenderReport`` the
session fills; an F12 render uses the scene's settings.
"""

from __future__ import annotations

import time
import traceback

import numpy as np

from . import kernel_cache

kernel_cache.configure()  # before anything below imports a tracer kernel module

from .export import export_scene  # noqa: E402
from .export.border import render_border  # noqa: E402
from .export.settings import export_settings  # noqa: E402
from .fingerprint import render_fingerprint  # noqa: E402
from .render_engine import enabled_passes  # noqa: E402
from .render_request import FilmSnapshot, RenderReport, RenderRequest  # noqa: E402
from .tracer.errors import PrismInputError  # noqa: E402


class _Cancelled(Exception):
    """A stop (Esc, Ctrl-C) was requested while a pass was running."""


class RenderSession:
    """Renders one frame of ``depsgraph`` through ``engine`` (a ``PrismRenderEngine``)
    as ``request`` asks (default: the scene's settings), filling ``report``."""

    def __init__(self, engine, depsgraph, request: RenderRequest | None = None, report: RenderReport | None = None):
        self.engine = engine
        self.depsgraph = depsgraph
        self.request = request or RenderRequest()
        self.report = report if report is not None else RenderReport()
        self.cancelled = False

    def fail(self, message: str) -> None:
        self.report.error = message
        self.engine.error_set(message)
        if self.request.progress_stream is None:  # a batch script prints the message once itself
            self.engine.report({"ERROR"}, message)

    def _print(self, line: str) -> None:
        stream = self.request.progress_stream
        if stream is not None:
            print(line, file=stream, flush=True)

    def stop_requested(self) -> bool:
        """Esc in Blender, or the request's own stop signal (Ctrl-C in a batch render)."""
        asked = self.request.stop_requested
        return bool(self.engine.test_break() or (asked is not None and asked()))

    def run(self) -> RenderReport:
        self.report.started = True
        try:
            self._render()
        except PrismInputError as error:
            self.fail(str(error))
        except MemoryError:
            self.fail("Prism ran out of memory: lower the resolution, the samples per pass or the thread count.")
        except Exception as error:  # noqa: BLE001 - a bug: one clear line in the report, details in the console
            traceback.print_exc()
            self.fail(f"Prism failed unexpectedly ({type(error).__name__}: {error}); details are in the console.")
        self.report.cancelled = self.report.cancelled or self.cancelled
        return self.report

    def _render(self) -> None:
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
        self.report.warnings = warnings
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
                self.report.film = FilmSnapshot(
                    mean=renderer.film.mean(),
                    samples=renderer.samples_done - req.sample_offset,
                    sample_offset=req.sample_offset,
                    seed=settings.seed,
                    fingerprint=render_fingerprint(tracer_scene, settings),
                )

    def _passes(self, renderer, border, width, height, target, warnings) -> None:
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
                if self.stop_requested():
                    self.cancelled = True
                    break
                done_before = renderer.samples_done - start_done

                def progress(fraction, done_before=done_before):
                    engine.update_progress(min(1.0, (done_before + fraction * per_pass) / target))
                    if self.stop_requested():
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
                self.report.stats = line
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
        rgba = np.concatenate([renderer.image_rgb(), renderer.image_alpha()[..., None]], axis=2)
        passes["Combined"].rect = bottom_up(rgba[y0:y1, x0:x1])
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
