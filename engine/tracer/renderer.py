"""The Renderer: progressive spectral path tracing of a ``Scene`` with compiled stages.

    renderer = Renderer(scene, settings, progress=None)
    renderer.render_pass()          # + settings.samples_per_pass samples per pixel
    renderer.image_rgb()            # float32 [H, W, 3] scene-linear Rec.709, row 0 = top
    renderer.image_alpha()          # float32 [H, W] (transparent film, holdouts; 1 otherwise)
    renderer.variance_rgb()         # float32 [H, W, 3] variance of the mean
    renderer.spectral_film          # SpectralFilm (band radiance) when settings.spectral_band_nm > 0, else None
    renderer.samples_done, renderer.strategy, renderer.stats
    renderer.tables                 # SceneTables: the triangles, their Embree scene, shading, analysis
    renderer.start_at_sample(n)     # continue the seed's sequence at sample n (chunked renders)
    renderer.finished               # every pixel has its samples, converged (adaptive) or time is up
    renderer.pass_images()          # the requested passes of the region: name -> float32 [h, w, C]
    renderer.set_region(box)        # render another rectangle (a tile) from sample 0, with a new film
    renderer.set_bake_rays(rays, pixels)  # a bake: the region's paths start from a ray table, not the camera
    renderer.cancel()               # from any thread: stop the current pass after running chunks
    renderer.close()                # free the thread pool (or use ``with Renderer(...) as r:``)

    # between passes (the viewport): rebuild only what changed, then the image starts again
    renderer.set_camera(camera, border)   renderer.set_shading(scene)
    renderer.set_geometry(scene)          renderer.set_settings(settings)   renderer.restart()

Set-up turns the scene into tables once (``scene_tables.SceneTables``: triangles and their Embree
scene, spectra, materials, lights, wavelength sampling, the scene analysis) and makes the camera, with
every position relative to the render's origin (the camera's position; the viewport keeps the first
one while the view moves). A pass is cut into chunks of paths that run on Prism's thread pool
(``chunk_pool``); a chunk (``chunk_tracer``) runs the stages of ``stages`` bounce by bounce, Embree
queries in between (kernels and Embree release the GIL). Every random number comes from the sampler
indexed by (pixel, sample, dimension) and the film adds samples in path order, so the image depends
on the seed only — not on the thread count or the chunk size.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from . import adaptive
from .cameras import make_camera
from .chunk_pool import ChunkPool
from .chunk_tracer import ChunkTracer
from .errors import PrismInputError
from .cryptomatte import scene_names
from .film import Film
from .sampler import SAMPLERS
from .spectra.glass import clamp_warnings
from .scene_tables import SceneTables
from .shadow_catcher_film import catcher_names, catcher_warnings
from .spectral_film import SpectralFilm
from .state import ChunkBuffers

#: A camera this far (m) from the render's origin gets the geometry rebuilt around it (``set_camera``):
#: float32 positions keep ~0.1 mm there.
REBASE_DISTANCE_M = 1000.0


def _check_settings(settings) -> None:
    settings.validate()  # the pixel filter and its width too
    if settings.sampler not in SAMPLERS:
        raise PrismInputError(f"Sampler '{settings.sampler}' is unknown: use one of {', '.join(SAMPLERS)}.")


class Renderer:
    def __init__(self, scene, settings, progress=None, origin=None):
        started = time.perf_counter()
        _check_settings(settings)
        scene.validate()
        self.scene = scene
        self.settings = settings
        self.progress = progress
        self.camera = make_camera(scene.camera, settings, origin)
        self.origin = self.camera.origin
        self.width, self.height = (int(r) for r in scene.camera.resolution)
        self.tables = SceneTables(scene, settings, self.camera)
        self._pool = ChunkPool(settings.threads)
        self._chunks = ChunkTracer()
        self.restart(time.perf_counter() - started)

    @property
    def strategy(self) -> str:
        """What the render does for this scene, in one line (``analysis``)."""
        return self.tables.strategy

    def restart(self, setup_seconds: float = 0.0) -> None:
        """Start the image again: an empty film and no samples, a cancelled renderer rendering again.
        Call it (as the ``set_*`` methods do) only while no pass runs."""
        self.spectral_film = (SpectralFilm(self.width, self.height, self.settings.spectral_band_nm)
                              if self.settings.spectral_band_nm else None)
        self._first_sample = 0
        self._passes = 0
        self._glass_clamps = np.zeros(len(self.tables.material_table.arrays.glasses), np.int64)
        self._pool.reset()
        self.cancelled = False
        self.set_region(self._frame_region(self.settings.border))
        dropped = self.tables.dropped_triangles
        warnings = [f"{dropped} zero-area triangle(s) dropped"] if dropped else []
        if self.camera.lens is not None:
            warnings += self.camera.lens.warnings
        if self.tables.kernel_settings.shadow_catcher:
            warnings += catcher_warnings(self.settings, catcher_names(self.scene))
        self.stats = {
            "rays_cast": 0,
            "seconds": 0.0,
            "setup_seconds": setup_seconds,
            "nan_samples": 0,
            "rejected_rays": 0,
            "dropped_triangles": dropped,
            "paths": 0,
            "warnings": warnings,
            "strategy": self.strategy,
            "light_paths": 0,
            "light_splats": 0,
        }

    # ---- changes between passes (the viewport): each rebuilds only the tables it touches ----------
    def set_camera(self, camera, border=None) -> None:
        """Render from ``camera`` (a ``scene.Camera``: placement, lens, resolution) with ``border``
        (a pixel rectangle of its resolution, see ``RenderSettings``; None: the whole frame), keeping
        the triangles, their Embree scene and the shading tables; the image restarts. The render's
        origin stays put unless the camera went further than ``REBASE_DISTANCE_M`` from it, when the
        geometry is rebuilt around the camera (float32 precision is kept near the viewer)."""
        started = time.perf_counter()
        scene = replace(self.scene, camera=camera)
        scene._validate_camera()
        self.scene = scene
        self.settings = replace(self.settings, border=border)
        position = np.asarray(camera.camera_to_world, dtype=np.float64)[:3, 3]
        rebase = np.abs(position - self.origin).max() > REBASE_DISTANCE_M
        self.camera = make_camera(camera, self.settings, position if rebase else self.origin)
        self.origin = self.camera.origin
        self.width, self.height = (int(r) for r in camera.resolution)
        if rebase:
            self.tables.rebuild(scene, self.settings, self.camera)
        else:
            self.tables.describe(scene, self.settings, self.camera)
        self.restart(time.perf_counter() - started)

    def set_shading(self, scene) -> None:
        """Materials, lights and world of ``scene``, whose triangles (and their material indices) are
        the ones being rendered (its camera is ignored); the image restarts."""
        started = time.perf_counter()
        scene = replace(scene, camera=self.scene.camera)
        scene.validate(triangles=False)
        self.scene = scene
        self.tables.rebuild_shading(scene, self.settings, self.camera)
        self.restart(time.perf_counter() - started)

    def set_geometry(self, scene) -> None:
        """Everything of ``scene`` but its camera: new triangles (and their Embree scene), materials,
        lights and world; the image restarts."""
        started = time.perf_counter()
        scene = replace(scene, camera=self.scene.camera)
        scene.validate()
        self.scene = scene
        self.tables.rebuild(scene, self.settings, self.camera)
        self.restart(time.perf_counter() - started)

    def set_settings(self, settings) -> None:
        """Render with ``settings`` (bounces, wavelengths, filter, seed, threads, border) from now on;
        the image restarts."""
        started = time.perf_counter()
        _check_settings(settings)
        self.settings = settings
        self.camera = make_camera(self.scene.camera, settings, self.origin)
        self.tables.rebuild_shading(self.scene, settings, self.camera)
        self._pool.resize(settings.threads)
        self.restart(time.perf_counter() - started)

    def _frame_region(self, border):
        """The rendered rectangle (x0, y0, x1, y1), rows from the top: the border, else the frame."""
        if border is None:
            return (0, 0, self.width, self.height)
        x0, y0, x1, y1 = (int(b) for b in border)
        x0, x1 = max(0, x0), min(self.width, x1)
        y0, y1 = max(0, y0), min(self.height, y1)
        if x1 <= x0 or y1 <= y0:
            raise PrismInputError("The render border is empty: enlarge it or turn it off.")
        return (x0, y0, x1, y1)

    def set_region(self, region, time_limit_s: float | None = None) -> None:
        """Render the rectangle ``region`` (x0, y0, x1, y1; rows from the top) from the first sample with
        a film of its own (tiles of a large frame: one tile's film in memory at a time).
        ``time_limit_s`` overrides the settings' time limit for it."""
        self.region = tuple(int(v) for v in region)
        self._film = None  # allocated when first used: a frame that is tiled never holds a whole-frame film
        self._region_pixels = self._pixels = None
        self.bake_rays = None  # a new region starts from the camera again
        self.samples_done = self._first_sample
        self._passes = self._first_sample // self.settings.samples_per_pass
        limit = self.settings.time_limit_s if time_limit_s is None else time_limit_s
        self._time_limit = float(limit) if limit and limit > 0 else None
        self._sampling_started = None
        self._sampling_seconds = 0.0
        self._converged_checked_at = 0
        self.converged = False
        self.time_up = False

    def set_bake_rays(self, rays, pixels) -> None:
        """Bake the region set last: its paths start from ``rays`` (``stages.bake_camera.BakeRays``, covering
        that region) instead of the camera, at ``pixels`` only (frame pixel indices, int64: the texels that
        have a surface point). Light tracing stays off (its paths would splat through the camera) and
        adaptive sampling must be off (it counts the region's every pixel). From then on the first-hit Normal
        and AO passes take the shading normal (``KernelSettings.shaded_normals``)."""
        if self.tables.analysis.light_tracing or self.settings.adaptive_threshold > 0.0:
            raise ValueError("a bake renders without light tracing and adaptive sampling")
        self.bake_rays = rays
        self._region_pixels = self._pixels = np.ascontiguousarray(pixels, dtype=np.int64)
        tables = self.tables
        if not tables.kernel_settings.shaded_normals:  # Normal and AO at the bumped normal, as Cycles bakes
            tables.kernel_settings = tables.kernel_settings._replace(shaded_normals=True)
            tables.arrays = tables.arrays._replace(settings=tables.kernel_settings)

    @property
    def film(self) -> Film:
        """The region's film."""
        if self._film is None:
            self._film = Film(self.width, self.height, self.tables.pass_layout, self.region)
            self._film.exposure = float(self.settings.film_exposure)
            self._film.film_transparent = bool(self.settings.film_transparent)
        return self._film

    def _region_pixel_list(self) -> np.ndarray:
        if self._region_pixels is None:
            x0, y0, x1, y1 = self.region
            rows = np.arange(y0, y1, dtype=np.int64)[:, None] * self.width
            self._region_pixels = (rows + np.arange(x0, x1, dtype=np.int64)[None, :]).ravel()
            self._pixels = self._region_pixels
        return self._pixels

    @property
    def finished(self) -> bool:
        """True when the region has its samples, every pixel has converged, or the time limit is up."""
        return (self.samples_done - self._first_sample >= self.settings.samples or self.converged
                or self.time_up or self.cancelled)

    @property
    def active_pixels(self) -> int:
        """Pixels the next pass samples (fewer than the region's once adaptive sampling stops some)."""
        return len(self._region_pixel_list())

    def pass_data(self, buffers: ChunkBuffers):
        """The per-path pass storage of ``buffers`` with this render's camera and AOV tables."""
        axes = np.asarray(self.scene.camera.camera_to_world, np.float64)[:3, :3]
        return buffers.passes._replace(camera_axes=np.ascontiguousarray(axes),
                                       camera_at=np.asarray(self.camera.position - self.origin, np.float64),
                                       render_origin=np.asarray(self.origin, np.float64),
                                       aov_table=self.tables.aov_table, aov_registers=self.tables.aov_registers,
                                       **self.tables.first_hit._asdict())

    def start_at_sample(self, first_sample: int) -> None:
        """Continue the seed's sample sequence from sample ``first_sample`` (a multiple of
        ``samples_per_pass``), before the first pass: chunks of a render made this way
        merge bit-identically with one render of all samples. ``settings.samples`` more
        samples are then rendered (``samples_done`` counts from ``first_sample``)."""
        per_pass = self.settings.samples_per_pass
        first_sample = int(first_sample)
        if first_sample < 0 or first_sample % per_pass:
            raise PrismInputError(
                f"Chunk offset {first_sample} is not a multiple of Samples per Pass ({per_pass}): "
                "use --samples that is a multiple of the scene's Samples per Pass."
            )
        if self._passes != self._first_sample // per_pass or self.samples_done != self._first_sample:
            raise RuntimeError("start_at_sample must be called before the first pass")
        self._first_sample = first_sample
        self.samples_done = first_sample
        self._passes = first_sample // per_pass

    def cancel(self) -> None:
        """Stop the pass in progress (thread-safe, returns at once): queued chunks are
        dropped, running ones finish; ``render_pass`` then returns early without
        counting the pass (and later passes do nothing until ``restart``). The film
        keeps the chunks already added."""
        self._pool.cancel()

    def render_pass(self, samples_per_pixel: int | None = None) -> None:
        """Add ``samples_per_pixel`` samples (default ``settings.samples_per_pass``, which callers never
        rewrite; fewer on the last pass or near a time limit) to every pixel."""
        if self._pool.cancelled:
            self.cancelled = True
            return
        started = time.perf_counter()
        if self._sampling_started is None:
            self._sampling_started = started
        remaining = self.settings.samples - (self.samples_done - self._first_sample)
        wanted = self.settings.samples_per_pass if samples_per_pixel is None else max(1, int(samples_per_pixel))
        spp = min(wanted, remaining) if remaining > 0 else wanted
        self._region_pixel_list()
        spp = self._fit_time_limit(spp, started)
        if spp == 0 or len(self._pixels) == 0:
            return
        total = len(self._pixels) * spp
        chunks = [(a, b, False) for a, b in self._pool.chunks(total, spp)]
        if self.tables.analysis.light_tracing:  # as many light paths as camera paths, numbered the same way
            chunks += [(a, b, True) for a, b, _ in chunks]
        light_splats = []  # (pixel, rgb, paths) of the pass's light chunks, in chunk order
        try:
            for i, got in self._pool.run(chunks, lambda a, b, light: self._chunks.trace(self, a, b, spp, light)):
                if chunks[i][2]:
                    light_splats.append((got.pixel, got.rgb, chunks[i][1] - chunks[i][0]))
                else:
                    self.film.add(got.pixel, got.rgb, got.values)
                    if got.alpha is not None:
                        self.film.add_alpha(got.pixel, got.alpha)
                    if got.spectral is not None:
                        self.spectral_film.add(got.pixel, *got.spectral)
                self.stats["rays_cast"] += got.rays
                self.stats["rejected_rays"] += got.rejected
                self._glass_clamps += got.clamps
                if self.progress is not None:
                    self.progress((i + 1) / len(chunks))
        finally:
            self._pool.drop()
            if light_splats:  # all at once: see ``stages.light_splat``
                self.stats["light_paths"] += self.film.add_light_chunks(light_splats)
                self.stats["light_splats"] += sum(len(pixels) for pixels, _, _ in light_splats)
            elapsed = time.perf_counter() - started
            self.stats["seconds"] += elapsed
            self._sampling_seconds += elapsed
        if self._pool.cancelled:
            self.cancelled = True
            return
        self.samples_done += spp
        self._passes += 1
        self._last_pass = (elapsed, spp * len(self._pixels))
        clamp_warnings(self.tables.material_table.glasses, self._glass_clamps, self.stats["warnings"])
        self.stats["paths"] += total
        self.stats["nan_samples"] = self.film.nan_samples
        self.stats["samples"] = self.samples_done
        self._adapt()

    def _fit_time_limit(self, spp: int, now: float) -> int:
        """Samples of the next pass that fit in the time left (0: the time is up)."""
        if self._time_limit is None:
            return spp
        left = self._time_limit - (now - self._sampling_started)
        self.time_up = self.time_up or left <= 0.0
        last = getattr(self, "_last_pass", None) if self._passes > 0 else None
        return adaptive.samples_that_fit(spp, left, last, len(self._pixels))

    def _adapt(self) -> None:
        """Adaptive sampling: after the minimum samples, sample only the pixels that are still noisy."""
        threshold = self.settings.adaptive_threshold
        done = self.samples_done - self._first_sample
        if not adaptive.time_to_check(threshold, done, self.settings, self._converged_checked_at):
            return
        self._converged_checked_at = done
        self._pixels = self._region_pixels[adaptive.still_active(self.film, threshold, done)]
        if not len(self._pixels):
            self.converged = True

    def frame_mean(self) -> np.ndarray:
        """The film's float64 mean as a whole frame [H, W, 3] (0 outside the region)."""
        return self.film.in_frame(self.film.mean())

    def sample_counts(self) -> np.ndarray:
        """Samples per pixel as a whole frame, int64 [H, W] (0 outside the region)."""
        return self.film.in_frame(self.film.counts)

    def image_rgb(self) -> np.ndarray:
        """Combined: mean radiance, scene-linear Rec.709, float32 [H, W, 3], row 0 = top (0 outside the
        region); with a shadow catcher, as Cycles makes it (``Film.combined``)."""
        return self.film.in_frame(self.film.combined()[0].astype(np.float32))

    def image_alpha(self) -> np.ndarray:
        """Combined's alpha, float32 [H, W], row 0 = top (``image_rgb`` is premultiplied by it; 1 outside the
        region)."""
        return self.film.in_frame(self.film.combined()[1].astype(np.float32), fill=1.0)

    def variance_rgb(self) -> np.ndarray:
        """Per-pixel variance of the mean estimate, float32 [H, W, 3] (0 outside the region)."""
        return self.film.in_frame(self.film.variance_of_mean().astype(np.float32))

    def pass_images(self) -> dict[str, np.ndarray]:
        """The requested passes of the region (``settings.passes``): Blender pass name → float32 [h, w, C]."""
        layout = self.tables.pass_layout
        images = layout.images(self.film.aux_mean(), exposure=self.settings.film_exposure) if layout.width else {}
        if "Shadow Catcher" in layout.request.passes:
            images["Shadow Catcher"] = self.film.shadow_catcher().astype(np.float32)
        if layout.cryptomatte_column >= 0:
            images.update(self.film.cryptomatte_images(scene_names(self.scene)))
        return images

    def close(self) -> None:
        """Cancel outstanding work and free the thread pool (idempotent)."""
        self._pool.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self._pool.close_now()
        except Exception:
            pass
