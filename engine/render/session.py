"""One F12 or batch render: export, progressive passes, Render Result updates.

Imported only when a render starts (it pulls in the tracer: numpy, embreex,
colour-science). A batch script hands its overrides over with
``engine.render.request.render_request`` and reads the ``RenderReport`` the
session fills; an F12 render uses the scene's settings.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import replace

import numpy as np

from ..warmup import kernel_cache

kernel_cache.configure()  # before anything below imports a tracer kernel module

from ..output import spectral_exr  # noqa: E402
from ..output.denoise import denoise as denoise_image  # noqa: E402
from ..export import export_scene  # noqa: E402
from ..export.border import render_border  # noqa: E402
from ..export.settings import export_settings  # noqa: E402
from ..tracer.cryptomatte import scene_names  # noqa: E402
from .cryptomatte_metadata import stamp_cryptomatte  # noqa: E402
from .fingerprint import render_fingerprint  # noqa: E402
from .result_passes import bottom_up, denoising, enabled_passes, frame_plan, pass_request, write_passes  # noqa: E402
from .request import FilmSnapshot, RenderReport, RenderRequest  # noqa: E402
from .stats import stats_line, timecode  # noqa: E402
from .stereo import render_views  # noqa: E402
from ..tracer.errors import PrismInputError  # noqa: E402
from ..tracer.shadow_catcher_film import catcher_names  # noqa: E402


#: During a whole-frame render the Render Result is refreshed after the first pass, then at most this
#: often, and after the last: copying an image into Blender's result takes ~50 ms even at 480 x 320, more
#: than a 1-sample pass of a small frame (Cycles, too, refreshes its display at intervals).
DISPLAY_INTERVAL_S = 1.0


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

    def _report(self, kind: str, message: str) -> None:
        """One line per message: a batch render prints it on its progress stream, F12 reports it to Blender.
        Not both: in background mode Blender prints every report on stdout as well (``BKE_report``)."""
        if self.request.progress_stream is not None:
            self._print(f"Prism: {kind.lower()}: {message}")
        else:
            self.engine.report({kind}, message)

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
            if self.request.show_image is not None:
                self._show(self.request.show_image)
            else:
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
        from ..tracer.renderer import Renderer

        engine = self.engine
        scene = self.depsgraph.scene
        req = self.request
        kernel_cache.check_directory()
        if not self._wait_for_warmup():
            return
        compiling = kernel_cache.compiling_notice()
        notice = f" | {compiling}" if compiling else ""
        if compiling:
            self._print(f"Prism: {compiling}")
        engine.update_stats("", f"Prism | Exporting scene{notice}")
        warnings: list[str] = []
        # motion blur evaluates the shutter's times through the engine: the user's frame is left alone
        tracer_scene = export_scene(self.depsgraph, warnings, frame_set=lambda f, s: engine.frame_set(f, subframe=s))
        width, height = tracer_scene.camera.resolution
        border = render_border(scene, width, height)
        view_layer = self.depsgraph.view_layer
        spectral_path = spectral_exr.requested_path(scene, req, engine.is_preview)
        if spectral_path is not None:  # before rendering: a path that cannot be written fails in seconds
            spectral_exr.check_writable(spectral_path)
        settings = export_settings(
            scene, samples=req.samples, seed=req.seed, threads=req.threads, preview=engine.is_preview, border=border,
            passes=pass_request(scene, view_layer, for_render=True), spectral=spectral_path is not None,
        )
        self._apply_overrides(settings, warnings)
        views = render_views(engine, self.depsgraph, tracer_scene.camera, warnings)
        if len(views) > 1 and req.keep_film:
            raise PrismInputError(f"Scene '{scene.name}': Output ▸ Stereoscopy is on, but a chunk (--chunk-seed) "
                                  "holds one view: render stereo frames whole, or turn Stereoscopy off.")
        if len(views) > 1 and spectral_path is not None:
            warnings.append(f"Scene '{scene.name}': the spectral EXR holds the first view ('{views[0].name}') only; "
                            "the other views are in the Render Result.")
        self.report.warnings = warnings
        for message in warnings if not engine.is_preview else ():  # Blender's preview scene: not the user's to fix
            self._report("WARNING", message)
        for index, view in enumerate(views):
            engine.update_stats("", f"Prism | Preparing (BVH, spectra){notice}")
            seen = tracer_scene if view.camera is tracer_scene.camera else replace(tracer_scene, camera=view.camera)
            with Renderer(seen, settings) as renderer:
                # The spectral film and the spectral EXR's RGB cover the whole frame: no tiles then.
                plan = self._plan(renderer, scene, view_layer, width, height, whole=spectral_path is not None)
                if req.sample_offset:
                    renderer.start_at_sample(req.sample_offset)
                if req.keep_film and renderer.tables.kernel_settings.shadow_catcher:
                    names = ", ".join(f"'{n}'" for n in catcher_names(tracer_scene))
                    renderer.stats["warnings"].append(
                        f"Shadow catcher {names}: a sample chunk (--chunk-seed) keeps Combined as rendered, with the "
                        "catcher as an ordinary object, so merged chunks show it so; render the frame whole for its "
                        "matte and shadow.")
                try:
                    self._passes(renderer, plan, border or (0, 0, width, height), warnings, view.name)
                finally:
                    if self.cancelled:
                        renderer.cancel()  # drop queued chunks: Esc returns within a chunk's time
                if index == 0 and not self.cancelled:
                    stamp_cryptomatte(engine, view_layer.name, settings.passes, scene_names(tracer_scene))
                self._report_tracer_warnings(renderer, warnings)
                if self.cancelled:
                    return
                if compiling:
                    kernel_cache.mark_compiled()
                if spectral_path is not None and index == 0:
                    self._write_spectral(renderer, spectral_path)
                if req.keep_film:
                    self.report.film = FilmSnapshot(
                        mean=renderer.frame_mean(),
                        samples=renderer.samples_done - req.sample_offset,
                        sample_offset=req.sample_offset,
                        seed=settings.seed,
                        fingerprint=render_fingerprint(tracer_scene, settings,
                                                       scene.frame_current + scene.frame_subframe),
                    )

    def _wait_for_warmup(self) -> bool:
        """While the kernels compile in a background warm-up (``engine.warmup``), wait for it instead of
        compiling them a second time alongside it: waiting costs what the warm-up has left, never more
        than a compile from scratch, and two compiles at once would share the same cores. False if
        stopped meanwhile (Esc, Ctrl-C)."""
        if kernel_cache.compiling_notice() is None:
            return True
        from ..warmup import launch

        if launch.running() is None:
            return True
        self._print(f"Prism: {kernel_cache.WAITING_MESSAGE}")

        def report(seconds: float) -> None:
            self.engine.update_stats("", f"Prism | {kernel_cache.WAITING_MESSAGE} | {seconds:.0f} s")

        if launch.wait(self.stop_requested, report):
            return True
        self.cancelled = True
        self.engine.update_stats("", "Prism | Cancelled while the kernels were compiling")
        self._print("Prism: cancelled")
        return False

    def _apply_overrides(self, settings, warnings) -> None:
        """The request's sampling overrides; a sample chunk samples every pixel alike."""
        req = self.request
        if req.noise_threshold is not None:
            settings.adaptive_threshold = float(req.noise_threshold)
        if req.min_samples is not None:
            settings.adaptive_min_samples = int(req.min_samples)
        if req.time_limit_s is not None:
            settings.time_limit_s = float(req.time_limit_s)
        if req.keep_film and (settings.adaptive_threshold > 0 or settings.time_limit_s > 0):
            warnings.append("A sample chunk renders all its samples in every pixel: the noise threshold and time "
                            "limit are ignored (chunks could not merge otherwise)")
            settings.adaptive_threshold = 0.0
            settings.time_limit_s = 0.0
        settings.validate()

    def _show(self, image: np.ndarray) -> None:
        """Fill the Render Result with a finished image (see ``RenderRequest.show_image``)."""
        height, width = image.shape[:2]
        result = self.engine.begin_result(0, 0, width, height, layer=self.depsgraph.view_layer.name)
        try:
            result.layers[0].passes["Combined"].rect = bottom_up(np.asarray(image, np.float32), alpha=True)
        finally:
            self.engine.end_result(result)

    def _plan(self, renderer, scene, view_layer, width, height, whole=False):
        """Tiles and the memory check (a sample chunk keeps its whole film: never tiled)."""
        return frame_plan(scene, view_layer, width, height, renderer.region,
                          whole_film=whole or self.request.keep_film)

    def _passes(self, renderer, plan, border, warnings, view: str = "") -> None:
        """Every tile to all its samples, written to Blender's result (its ``view``: '' unless the render is
        stereo) as it finishes."""
        engine = self.engine
        scene = self.depsgraph.scene
        enabled = enabled_passes(scene, self.depsgraph.view_layer)
        for name, channels, ids, _ in enabled:
            engine.add_pass(name, channels, ids)
        wanted = {name for name, *_ in enabled}
        bx0, by0, bx1, by1 = border
        layer = self.depsgraph.view_layer.name
        limit = renderer.settings.time_limit_s
        started = time.perf_counter()
        tiles = plan.tiles
        if plan.tiled and denoising(scene):
            warnings.append(f"The frame is rendered in {len(tiles)} tiles and denoised tile by tile: enlarge "
                            "Performance ▸ Tile Size to denoise it whole")
        for index, tile in enumerate(tiles):
            if index and self.stop_requested():
                self.cancelled = True
                break
            budget = None
            if limit > 0:
                budget = max(0.0, (limit - (time.perf_counter() - started)) / (len(tiles) - index))
            renderer.set_region(tile, budget)
            x0, y0, x1, y1 = tile
            # Blender counts result rows from the bottom of the border.
            result = engine.begin_result(x0 - bx0, by1 - y1, x1 - x0, y1 - y0, layer=layer, view=view)
            try:
                self._sample(renderer, result, wanted, warnings, (index, len(tiles)))
            finally:
                engine.end_result(result)
            if self.cancelled:
                break

    def _sample(self, renderer, result, wanted, warnings, tile) -> None:
        """Passes of samples until the region is finished, the image shown as it refines (whole frames:
        ``DISPLAY_INTERVAL_S``)."""
        engine = self.engine
        req = self.request
        settings = renderer.settings
        per_pass = settings.samples_per_pass
        start_done = renderer.samples_done
        target = settings.samples
        started = time.perf_counter()
        pass_index = 0
        shown, shown_pass = None, 0  # when the Render Result was last refreshed, and after which pass
        index, count = tile
        quick = req.quick_first_pass and per_pass > 1 and count == 1

        def overall(fraction):
            return min(1.0, (index + fraction) / count)

        while not renderer.finished:
            if self.stop_requested():
                self.cancelled = True
                break
            done_before = renderer.samples_done - start_done

            def progress(fraction, done_before=done_before):
                engine.update_progress(overall((done_before + fraction * per_pass) / target))
                if self.stop_requested():
                    renderer.cancel()
                    raise _Cancelled

            renderer.progress = progress
            try:
                renderer.render_pass(1 if quick and pass_index == 0 else None)
            except _Cancelled:
                self.cancelled = True
            pass_index += 1
            final = renderer.finished or self.cancelled
            due = shown is None or time.perf_counter() - shown >= DISPLAY_INTERVAL_S
            if final or (count == 1 and due):
                self._write(result, renderer, wanted, denoise=final and not self.cancelled)
                engine.update_result(result)
                shown, shown_pass = time.perf_counter(), pass_index
            done = renderer.samples_done - start_done
            engine.update_progress(overall(done / target))
            line = stats_line(renderer, pass_index, done, target, time.perf_counter() - started, warnings, tile,
                              quote_warning=False)
            engine.update_stats("", line)
            self.report.stats = line
            # Blender's "Time: …" line, once per pass: render farms (Flamenco) count these as steps.
            self._print(f"Time: {timecode(time.perf_counter() - started)} | {line}")
            if self.cancelled:
                break
        if shown_pass != pass_index and renderer.samples_done > start_done:  # stopped between refreshes
            self._write(result, renderer, wanted, denoise=False)
            engine.update_result(result)
        if self.cancelled:
            engine.update_stats("", f"Prism | Cancelled at {renderer.samples_done - start_done}/{target} spp")
            self._print("Prism: cancelled")

    def _report_tracer_warnings(self, renderer, exported: list[str]) -> None:
        """The tracer's own warnings (a lens, a glass used outside its range), once each, as they stand at the
        end of the render (of each view: ``exported`` grows, so a second view repeats none); the status line
        only counts them."""
        found = [m for m in renderer.stats.get("warnings") or [] if m not in exported]
        exported.extend(found)
        self.report.warnings = exported
        for message in found if not self.engine.is_preview else ():
            self._report("WARNING", message)

    def _write_spectral(self, renderer, path) -> None:
        """The multispectral EXR; when it cannot be written the render itself stands (its image is kept, the
        failure is in ``report.output_errors``)."""
        film = renderer.spectral_film
        try:
            # Film ▸ Exposure scales the spectral bands as it scales their RGB image.
            bands = film.mean() * renderer.settings.film_exposure
            written = spectral_exr.write_spectral_exr(path, film.centres_nm, bands, renderer.image_rgb())
        except Exception as error:  # noqa: BLE001 - a secondary output never costs the render
            if not isinstance(error, PrismInputError):
                traceback.print_exc()
            message = f"The spectral EXR was not written ({error}); the rendered image is kept."
            self.report.output_errors.append(message)
            if self.request.progress_stream is None:  # a batch script prints it once itself, as ``fail``
                self.engine.report({"ERROR"}, message)
            return
        self.report.spectral_output = str(written)
        if self.request.progress_stream is None:  # a batch script names the files it wrote itself
            self.engine.report({"INFO"}, f"Prism: spectral image ({film.bands} bands of {film.band_nm:.3g} nm) "
                                         f"written to {written}")

    def _write(self, result, renderer, wanted, denoise: bool) -> None:
        """The region's Combined (denoised on the final pass when asked) and passes into ``result``."""
        passes = result.layers[0].passes
        scene = self.depsgraph.scene
        image, alpha = renderer.film.combined()  # with a shadow catcher, Cycles' matte (``Film.combined``)
        image = image.astype(np.float32)
        images = renderer.pass_images()
        if denoising(scene):
            images["Noisy Image"] = image
            if denoise:
                prism = scene.prism
                image = denoise_image(image, images["Denoising Albedo"], images["Denoising Normal"],
                                      prefilter=prism.denoising_prefilter, quality=prism.denoising_quality)
        alpha = alpha.astype(np.float32)[..., None]  # transparent film, holdouts (else 1)
        passes["Combined"].rect = bottom_up(np.concatenate([image, alpha], axis=2))
        if "Noise" in wanted:
            images["Noise"] = renderer.film.variance_of_mean().astype(np.float32)
        if "Sample Count" in wanted:
            images["Sample Count"] = renderer.film.counts.astype(np.float32)[..., None]
        write_passes(passes, images, wanted)
