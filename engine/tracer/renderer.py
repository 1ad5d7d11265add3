"""The Renderer API (see TEAM.md): progressive spectral path tracing of a ``Scene``.

    renderer = Renderer(scene, settings, progress=None)
    renderer.render_pass()          # + settings.samples_per_pass samples per pixel
    renderer.image_rgb()            # float32 [H, W, 3] scene-linear Rec.709, row 0 = top
    renderer.variance_rgb()         # float32 [H, W, 3] variance of the mean
    renderer.samples_done, renderer.strategy, renderer.stats
    renderer.start_at_sample(n)     # continue the seed's sequence at sample n (chunked renders)
    renderer.cancel()               # from any thread: stop the current pass after running chunks
    renderer.close()                # free the thread pools (or use ``with Renderer(...) as r:``)

A pass is cut into fixed-size chunks of paths (independent of the thread count,
so the seed alone fixes the image); chunks run on a thread pool, Embree and the
large numpy kernels release the GIL. Pixel positions come from a per-pixel
rotated R2 sequence indexed by the pixel's sample number; with the "box" filter
they are uniform in the pixel, with "gaussian" they follow a Gaussian of
standard deviation ``filter_width_px`` / 3 truncated at ``filter_width_px``
(filter importance sampling, weight 1). ``progress(fraction)`` is called after
each chunk with the fraction of the current pass done.
"""

from __future__ import annotations

import threading
import time
from concurrent.futures import CancelledError, ThreadPoolExecutor

import numpy as np

from . import path_spectra as spectra
from .accel import Accel, _threads
from .analysis import analyse
from .bsdf import make_bsdf
from .cameras import make_camera
from .errors import PrismInputError
from .film import Film
from .integrator import Integrator
from .lights import LightSet
from .path_state import TriangleData
from .sampling import pass_rng, pixel_offsets, r1_samples, r2_samples

CHUNK_PATHS = 1 << 15  # largest wavefront one thread traces at once
MIN_CHUNK_PATHS = 2048  # below this, per-bounce Python overhead dominates


def chunk_size(path_count: int) -> int:
    """Paths per chunk: at least two chunks when there is enough work, so both cores
    trace; depends only on the pass size (never the thread count), so seeds stay exact."""
    return int(max(MIN_CHUNK_PATHS, min(CHUNK_PATHS, -(-path_count // 2))))


def _filter_offsets(u, kind, width):
    if kind == "box":
        return u
    from scipy.special import ndtr, ndtri

    sigma = width / 3.0
    lo = ndtr(-width / sigma)
    p = lo + u * (1.0 - 2.0 * lo)
    return 0.5 + sigma * ndtri(np.clip(p, 1e-12, 1 - 1e-12))


class Renderer:
    def __init__(self, scene, settings, progress=None):
        started = time.perf_counter()
        settings.validate()
        scene.validate()
        self.scene = scene
        self.settings = settings
        self.progress = progress
        self.pixel_filter = settings.pixel_filter
        self.filter_width = float(settings.filter_width_px)
        if self.pixel_filter not in ("box", "gaussian") or not self.filter_width > 0:
            raise PrismInputError(f"Pixel filter '{self.pixel_filter}' is not supported: use box or gaussian.")
        self.camera = make_camera(scene.camera, settings)
        width, height = (int(r) for r in scene.camera.resolution)
        self.width, self.height = width, height
        used = set(np.unique(np.asarray(scene.triangle_material)).tolist()) if len(scene.triangles) else set()
        self.bsdfs = [make_bsdf(m, spectra) if i in used else None for i, m in enumerate(scene.materials)]
        self.analysis = analyse(scene, settings, self.bsdfs, self.camera)
        lines = spectra.monochromatic_lines(scene, self.analysis.used_materials)
        self.mode = spectra.WavelengthMode(settings, lines)
        self.analysis.guided_lines = len(lines) if self.mode.guided is not None else 0
        self.accel = Accel(scene.vertices, scene.triangles, settings.threads)
        self.lights = LightSet(scene, spectra, use_mesh_lights=self.analysis.mesh_lights)
        self.integrator = Integrator(
            self.accel, TriangleData(scene), self.bsdfs, self.lights, self.mode, self.camera, settings, self.analysis
        )
        self.film = Film(width, height)
        self._pixels = self._pixel_list(settings.border)
        count = width * height
        self._rot_pixel = pixel_offsets(settings.seed, count, 2, 1)
        self._rot_lens = pixel_offsets(settings.seed, count, 2, 2)
        self._rot_lambda = pixel_offsets(settings.seed, count, 1, 3)[:, 0]
        self._workers = _threads(settings.threads)
        self._pool = ThreadPoolExecutor(self._workers)
        self._cancel = threading.Event()
        self._jobs_lock = threading.Lock()
        self._jobs = {}
        self.samples_done = 0
        self._first_sample = 0
        self._passes = 0
        self.cancelled = False
        self.strategy = self.analysis.strategy(settings.use_mis, self.pixel_filter)
        warnings = []
        if self.accel.dropped_triangles:
            warnings.append(f"{self.accel.dropped_triangles} zero-area triangle(s) dropped")
        self.stats = {
            "rays_cast": 0,
            "seconds": 0.0,
            "setup_seconds": time.perf_counter() - started,
            "nan_samples": 0,
            "rejected_rays": 0,
            "dropped_triangles": self.accel.dropped_triangles,
            "paths": 0,
            "warnings": warnings,
            "strategy": self.strategy,
        }

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

    def _paths(self, start, stop, spp):
        """Pixel index and sample number of paths ``start:stop`` of this pass."""
        path = np.arange(start, stop, dtype=np.int64)
        return self._pixels[path // spp], self.samples_done + path % spp

    def _chunk(self, start, stop, spp, chunk_index):
        rng = pass_rng(self.settings.seed, self._passes, chunk_index)
        pixel, sample = self._paths(start, stop, spp)
        n = len(pixel)
        xy = np.column_stack([pixel % self.width, pixel // self.width]).astype(np.float64)
        xy += _filter_offsets(r2_samples(sample, self._rot_pixel[pixel]), self.pixel_filter, self.filter_width)
        lens_uv = r2_samples(sample, self._rot_lens[pixel])
        if self.mode.dimensions == 1:
            u_lam = r1_samples(sample, self._rot_lambda[pixel])[:, None]
        else:
            u_lam = rng.random((n, 3))
        lam, lam_pdf = self.mode.sample(u_lam)
        hero = rng.integers(0, lam.shape[1], n)
        radiance, rays = self.integrator.trace(xy, lens_uv, lam, hero, rng)
        return pixel, self.mode.to_rgb(radiance, lam, lam_pdf), rays

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
        self._passes = first_sample // per_pass  # the pass index seeds the pass's random numbers

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
        bounds = list(range(0, total, chunk_size(total))) + [total]
        chunks = list(zip(bounds[:-1], bounds[1:]))
        window = 2 * self._workers  # chunks in flight: bounded memory for huge frames
        jobs = self._jobs
        try:
            for i in range(len(chunks)):
                with self._jobs_lock:
                    for j in range(i, min(i + window, len(chunks))):
                        if j not in jobs and not self._cancel.is_set():
                            jobs[j] = self._pool.submit(self._chunk, *chunks[j], spp, j)
                job = jobs.get(i)
                if job is None:
                    break
                try:
                    pixel, rgb, rays = job.result()
                except CancelledError:
                    break
                with self._jobs_lock:
                    del jobs[i]
                self.film.add(pixel, rgb)
                self.stats["rays_cast"] += rays
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
        self.stats["rejected_rays"] = self.accel.rejected_rays
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
        for b in self.bsdfs:
            glass = getattr(b, "glass", None)
            count = int(getattr(glass, "out_of_range_count", 0) or 0)
            if count:
                lo, hi = glass.valid_range_nm
                text = (f"Glass '{glass.name}' is specified for {lo:g}-{hi:g} nm only: "
                        f"the index was clamped at the range edge for {{}} wavelength sample(s)")
                msgs = self.stats["warnings"]
                msgs[:] = [m for m in msgs if not m.startswith(text.split("{")[0])] + [text.format(count)]

    def image_rgb(self) -> np.ndarray:
        """Mean radiance, scene-linear Rec.709, float32 [H, W, 3], row 0 = top."""
        return self.film.mean().astype(np.float32)

    def variance_rgb(self) -> np.ndarray:
        """Per-pixel variance of the mean estimate, float32 [H, W, 3]."""
        return self.film.variance_of_mean().astype(np.float32)

    def close(self) -> None:
        """Cancel outstanding work and free the thread pools (idempotent)."""
        self._cancel.set()
        self._drop_jobs()
        self._pool.shutdown(wait=True, cancel_futures=True)
        self.accel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self.accel.close()
        except Exception:
            pass
