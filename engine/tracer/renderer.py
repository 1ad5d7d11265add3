"""The Renderer: progressive spectral path tracing of a ``Scene`` with compiled stages.

    renderer = Renderer(scene, settings, progress=None)
    renderer.render_pass()          # + settings.samples_per_pass samples per pixel
    renderer.image_rgb()            # float32 [H, W, 3] scene-linear Rec.709, row 0 = top
    renderer.image_alpha()          # float32 [H, W] (transparent film, holdouts; 1 otherwise)
    renderer.variance_rgb()         # float32 [H, W, 3] variance of the mean
    renderer.samples_done, renderer.strategy, renderer.stats
    renderer.start_at_sample(n)     # continue the seed's sequence at sample n (chunked renders)
    renderer.cancel()               # from any thread: stop the current pass after running chunks
    renderer.close()                # free the thread pool (or use ``with Renderer(...) as r:``)

Set-up turns the scene into tables once (``geometry``, ``spectra.table``, ``materials``, ``lights``,
``spectra.wavelength_sampling``, the camera) with every position relative to the camera. A pass is cut
into chunks of paths that run on Prism's thread pool; a chunk runs the stages of ``stages`` bounce by
bounce, Embree queries in between (kernels and Embree release the GIL). Every random number comes from
the sampler indexed by (pixel, sample, dimension) and the film adds samples in path order, so the image
depends on the seed only — not on the thread count or the chunk size.
"""

from __future__ import annotations

import os
import threading
import time
from concurrent.futures import CancelledError, ThreadPoolExecutor

import numpy as np

from .accel import Accel
from .analysis import SceneAnalysis
from .cameras import make_camera
from .errors import PrismInputError
from .film import Film
from .geometry import prepare_geometry
from .lights.table import build_lights
from .materials.table import MAT_DISPERSIVE, MAT_EMISSIVE, MAT_NULL, build_materials, is_emissive
from .sampler import SAMPLERS
from .spectra import wavelength_sampling
from .spectra.table import SpectrumTable
from .stages.settings import KernelSettings
from .state import ChunkBuffers
from .visibility import HOLDOUT
from .visibility_accel import RayClassAccel, needs_ray_classes

MAX_CHUNK_PATHS = 1 << 16  # largest chunk one thread traces at once (memory ~0.5 kB per path)
MIN_CHUNK_PATHS = 4096  # below this, per-bounce Python overhead dominates


def chunk_size(path_count: int, threads: int, samples_per_pixel: int = 1) -> int:
    """Paths per chunk: about two chunks per thread (load balance), within the bounds above, and a
    multiple of ``samples_per_pixel`` (a chunk never splits a pixel's samples of a pass: see ``film``)."""
    size = max(MIN_CHUNK_PATHS, min(MAX_CHUNK_PATHS, -(-path_count // (2 * max(threads, 1)))))
    return int(max(samples_per_pixel, size - size % samples_per_pixel))


def worker_threads(requested: int) -> int:
    return max(1, int(requested) if requested and requested > 0 else (os.cpu_count() or 1))


def _monochromatic_lines(scene, used):
    from .spectra.emission_spectrum import emission_spectrum

    specs = [light.spectrum for light in scene.lights if light.spectrum.kind == "monochromatic"]
    for m in used:
        material = scene.materials[m]
        if is_emissive(material) and material.emission is not None and material.emission.kind == "monochromatic":
            specs.append(material.emission)
    return [emission_spectrum(spec) for spec in dict.fromkeys(specs)]


class Renderer:
    def __init__(self, scene, settings, progress=None):
        started = time.perf_counter()
        settings.validate()
        scene.validate()
        if settings.pixel_filter not in ("box", "gaussian") or not settings.filter_width_px > 0:
            raise PrismInputError(f"Pixel filter '{settings.pixel_filter}' is not supported: use box or gaussian.")
        if settings.sampler not in SAMPLERS:
            raise PrismInputError(f"Sampler '{settings.sampler}' is unknown: use one of {', '.join(SAMPLERS)}.")
        self.scene = scene
        self.settings = settings
        self.progress = progress
        self.camera = make_camera(scene.camera, settings)
        self.width, self.height = (int(r) for r in scene.camera.resolution)
        self.geometry, self._original_triangle, dropped = prepare_geometry(scene, self.camera.position)
        used = sorted(set(np.unique(self.geometry.material).tolist()))
        if used and (used[0] < 0 or used[-1] >= len(scene.materials)):
            raise PrismInputError("Scene triangles reference a material index that does not exist: re-export the scene.")
        spectra = SpectrumTable()
        self.material_table = build_materials(scene.materials, set(used), spectra)
        materials = self.material_table.arrays
        self.light_table = build_lights(scene, spectra, self.geometry.vertices, self.geometry.triangles,
                                        self.geometry.material, materials.emission_strength, self.camera.position)
        self.analysis = self._analyse(used)
        lines = _monochromatic_lines(scene, used) if settings.wavelength_mode == "cie" else []
        self.wavelengths = wavelength_sampling.build(settings, lines)
        self.analysis.guided_lines = len(lines)
        self.spectra = spectra.arrays()
        self.kernel_settings = KernelSettings(int(settings.max_bounces), int(settings.russian_roulette_depth),
                                              bool(settings.use_mis), SAMPLERS[settings.sampler],
                                              int(settings.seed) & 0xFFFFFFFF, bool(settings.film_transparent),
                                              bool(settings.film_transparent and settings.transparent_glass),
                                              float(settings.transparent_roughness) ** 2)
        self.accel = Accel(self.geometry)
        self.ray_classes = RayClassAccel(self.geometry, self.accel) if needs_ray_classes(self.geometry) else None
        self._alpha = bool(settings.film_transparent) or bool((self.geometry.flags & HOLDOUT).any())
        self.film = Film(self.width, self.height)
        self._pixels = self._pixel_list(settings.border)
        self._workers = worker_threads(settings.threads)
        self._pool = ThreadPoolExecutor(self._workers)
        self._local = threading.local()
        self._cancel = threading.Event()
        self._jobs_lock = threading.Lock()
        self._jobs = {}
        self._glass_clamps = np.zeros(len(materials.glasses), np.int64)
        self.samples_done = 0
        self._first_sample = 0
        self._passes = 0
        self.cancelled = False
        self.strategy = self.analysis.strategy(settings.use_mis, settings.pixel_filter)
        warnings = []
        if dropped:
            warnings.append(f"{dropped} zero-area triangle(s) dropped")
        self.stats = {
            "rays_cast": 0,
            "seconds": 0.0,
            "setup_seconds": time.perf_counter() - started,
            "nan_samples": 0,
            "rejected_rays": 0,
            "dropped_triangles": dropped,
            "paths": 0,
            "warnings": warnings,
            "strategy": self.strategy,
        }

    def _analyse(self, used) -> SceneAnalysis:
        s = self.settings
        k = int(s.wavelengths_per_path) if s.wavelength_mode == "cie" else 3
        a = SceneAnalysis(s.wavelength_mode, k, list(used), sampler=s.sampler)
        flags = self.material_table.arrays.flags
        for m in used:
            if flags[m] & MAT_DISPERSIVE:
                material = self.scene.materials[m]
                a.dispersive.append(material.glass or material.name)
        a.mesh_lights = any(flags[m] & MAT_EMISSIVE for m in used)
        a.see_through_films = any(flags[m] & MAT_NULL for m in used)
        a.camera_disperses = self.camera.disperses
        a.camera_strategy = self.camera.strategy
        a.dispersion = bool(a.dispersive) or a.camera_disperses
        a.light_kinds = [light.kind for light in self.scene.lights]
        a.features = list(self.material_table.features)
        a.world = self.light_table.world
        return a

    def _pixel_list(self, border):
        if border is None:
            return np.arange(self.width * self.height, dtype=np.int64)
        x0, y0, x1, y1 = (int(b) for b in border)
        x0, x1 = max(0, x0), min(self.width, x1)
        y0, y1 = max(0, y0), min(self.height, y1)
        if x1 <= x0 or y1 <= y0:
            raise PrismInputError("The render border is empty: enlarge it or turn it off.")
        ys, xs = np.mgrid[y0:y1, x0:x1]
        return (ys * self.width + xs).ravel().astype(np.int64)

    def _buffers(self, paths: int) -> ChunkBuffers:
        buffers = getattr(self._local, "buffers", None)
        if buffers is None or buffers.capacity < paths:
            buffers = self._local.buffers = ChunkBuffers(paths, self.wavelengths.count)
        return buffers

    def _chunk(self, start, stop, spp):
        """Trace paths ``start .. stop`` of the pass; returns (pixel [n], rgb [n, 3], rays, counters)."""
        from .stages.trace import trace_chunk

        count = stop - start
        buffers = self._buffers(count)
        clamps = np.zeros_like(self._glass_clamps)
        rays, rejected = trace_chunk(self, buffers, start, count, spp, self.samples_done, clamps)
        alpha = 1.0 - buffers.state.transparency[:count] if self._alpha else None
        return buffers.state.pixel[:count].copy(), buffers.rgb[:count].copy(), rays, rejected, clamps, alpha

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
        if self._passes != self._first_sample // per_pass:
            raise RuntimeError("start_at_sample must be called before the first pass")
        self._first_sample = first_sample
        self.samples_done = first_sample
        self._passes = first_sample // per_pass

    def cancel(self) -> None:
        """Stop the pass in progress (thread-safe, returns at once): queued chunks are
        dropped, running ones finish; ``render_pass`` then returns early without
        counting the pass (and later passes do nothing). The film keeps the chunks
        already added."""
        self._cancel.set()
        with self._jobs_lock:
            jobs = list(self._jobs.values())
        for job in jobs:
            job.cancel()

    def render_pass(self) -> None:
        """Add ``samples_per_pass`` samples (fewer on the last pass) to every pixel."""
        if self._cancel.is_set():
            self.cancelled = True
            return
        started = time.perf_counter()
        remaining = self.settings.samples - (self.samples_done - self._first_sample)
        spp = min(self.settings.samples_per_pass, remaining) if remaining > 0 else self.settings.samples_per_pass
        total = len(self._pixels) * spp
        size = chunk_size(total, self._workers, spp)
        bounds = list(range(0, total, size)) + [total]
        chunks = list(zip(bounds[:-1], bounds[1:]))
        window = 2 * self._workers  # chunks in flight: bounded memory for huge frames
        jobs = self._jobs
        try:
            for i in range(len(chunks)):
                with self._jobs_lock:
                    for j in range(i, min(i + window, len(chunks))):
                        if j not in jobs and not self._cancel.is_set():
                            jobs[j] = self._pool.submit(self._chunk, *chunks[j], spp)
                job = jobs.get(i)
                if job is None:
                    break
                try:
                    pixel, rgb, rays, rejected, clamps, alpha = job.result()
                except CancelledError:
                    break
                with self._jobs_lock:
                    del jobs[i]
                self.film.add(pixel, rgb)
                if alpha is not None:
                    self.film.add_alpha(pixel, alpha)
                self.stats["rays_cast"] += rays
                self.stats["rejected_rays"] += rejected
                self._glass_clamps += clamps
                if self.progress is not None:
                    self.progress((i + 1) / len(chunks))
                if self._cancel.is_set():
                    break
        finally:
            self._drop_jobs()
            self.stats["seconds"] += time.perf_counter() - started
        if self._cancel.is_set():
            self.cancelled = True
            return
        self.samples_done += spp
        self._passes += 1
        self._glass_warnings()
        self.stats["paths"] += total
        self.stats["nan_samples"] = self.film.nan_samples
        self.stats["samples"] = self.samples_done

    def _drop_jobs(self):
        """Cancel queued chunks and wait for running ones (after a cancel or an error)."""
        with self._jobs_lock:
            jobs = list(self._jobs.values())
            self._jobs.clear()
        for job in jobs:
            job.cancel()
        for job in jobs:
            if not job.cancelled():
                try:
                    job.result()
                except Exception:  # noqa: BLE001 - the pass is abandoned anyway
                    pass

    def _glass_warnings(self):
        for glass, count in zip(self.material_table.glasses, self._glass_clamps):
            if count:
                lo, hi = glass.valid_range_nm
                prefix = f"Glass '{glass.name}' is specified for {lo:g}-{hi:g} nm only: "
                text = prefix + f"the index was clamped at the range edge for {count} wavelength sample(s)"
                messages = self.stats["warnings"]
                messages[:] = [m for m in messages if not m.startswith(prefix)] + [text]

    def image_rgb(self) -> np.ndarray:
        """Mean radiance, scene-linear Rec.709, float32 [H, W, 3], row 0 = top."""
        return self.film.mean().astype(np.float32)

    def image_alpha(self) -> np.ndarray:
        """Mean alpha, float32 [H, W], row 0 = top (premultiplied: ``image_rgb`` is already × alpha)."""
        return self.film.alpha().astype(np.float32)

    def variance_rgb(self) -> np.ndarray:
        """Per-pixel variance of the mean estimate, float32 [H, W, 3]."""
        return self.film.variance_of_mean().astype(np.float32)

    def close(self) -> None:
        """Cancel outstanding work and free the thread pool (idempotent)."""
        self._cancel.set()
        self._drop_jobs()
        self._pool.shutdown(wait=True, cancel_futures=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self._pool.shutdown(wait=False, cancel_futures=True)
        except Exception:
            pass
