"""Running Prism's Renderer for the harness: progressive error-vs-time curves.

Time of a checkpoint = Renderer construction (scene analysis, BVH build) + the
render passes so far, excluding the time to read the image back. Passes are
``PASS_SPP`` samples per pixel (fewer when a checkpoint is closer), so a 64 x 64
pass is 65,536 paths: two of the renderer's 32,768-path chunks, one per thread.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from engine.tracer.renderer import Renderer
from engine.tracer.settings import RenderSettings

PASS_SPP = 16


def settings_for(overrides: dict, samples: int, seed: int, threads: int) -> RenderSettings:
    """RenderSettings with the harness defaults (threads, seed) and ``overrides``."""
    base = RenderSettings(samples=samples, samples_per_pass=PASS_SPP, seed=seed, threads=threads)
    return replace(base, **overrides)


def progressive(scene, settings: RenderSettings, checkpoints, on_renderer=None):
    """Render up to max(checkpoints) spp; return a list of dicts (spp, seconds,
    image, rays_cast) at each checkpoint, and the renderer's stats."""
    checkpoints = sorted(set(int(c) for c in checkpoints))
    settings = replace(settings, samples=checkpoints[-1])
    start = time.perf_counter()
    renderer = Renderer(scene, settings)
    elapsed = setup = time.perf_counter() - start
    if on_renderer is not None:
        on_renderer(renderer)
    out = []
    try:
        for target in checkpoints:
            while renderer.samples_done < target:
                settings.samples_per_pass = min(PASS_SPP, target - renderer.samples_done)
                t0 = time.perf_counter()
                renderer.render_pass()
                elapsed += time.perf_counter() - t0
            out.append(dict(spp=renderer.samples_done, seconds=elapsed, setup=setup, image=renderer.image_rgb(),
                            rays_cast=int(renderer.stats["rays_cast"])))
        stats = dict(renderer.stats)
        stats["strategy"] = renderer.strategy
    finally:
        renderer.close()
    return out, stats


def converge(scene, settings: RenderSettings, samples: int, max_seconds: float):
    """A reference: render until ``samples`` spp or ``max_seconds``; returns
    (image, variance of the mean, spp reached, seconds, strategy)."""
    settings = replace(settings, samples=samples, samples_per_pass=PASS_SPP)
    start = time.perf_counter()
    renderer = Renderer(scene, settings)
    try:
        while renderer.samples_done < samples and time.perf_counter() - start < max_seconds:
            renderer.render_pass()
        return (renderer.image_rgb(), renderer.variance_rgb(), renderer.samples_done,
                time.perf_counter() - start, renderer.strategy)
    finally:
        renderer.close()


class InlineExecutor:
    """A stand-in thread pool that runs jobs at once in the caller's thread (for cProfile)."""

    def submit(self, fn, *args, **kwargs):
        from concurrent.futures import Future

        future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller through the future
            future.set_exception(exc)
        return future

    def shutdown(self, *args, **kwargs):
        pass


def profile_pass(scene, overrides: dict, top: int = 22) -> dict:
    """cProfile of one 16-spp pass, single-threaded, every chunk run in the main
    thread so the profiler sees it: ``text`` (top entries by own time),
    ``total`` seconds, ``functions`` {"file:line(name)": [own, cumulative]}."""
    import cProfile
    import io
    import pstats

    settings = settings_for(overrides, samples=2 * PASS_SPP, seed=99, threads=1)
    renderer = Renderer(scene, settings)
    renderer._pool.shutdown()
    renderer._pool = InlineExecutor()
    try:
        renderer.render_pass()  # warm-up: lazy tables, first-touch
        profiler = cProfile.Profile()
        profiler.enable()
        renderer.render_pass()
        profiler.disable()
    finally:
        renderer.close()
    stream = io.StringIO()
    stats = pstats.Stats(profiler, stream=stream)
    stats.sort_stats("tottime").print_stats(top)
    root = str(_repo_root()) + "/"
    text = "\n".join(ln.replace(root, "") for ln in stream.getvalue().splitlines() if ln.strip())
    functions = {}
    for (path, line, name), (_, _, own, cumulative, _) in stats.stats.items():
        functions[f"{path.replace(root, '')}:{line}({name})"] = [own, cumulative]
    return dict(text=text, total=stats.total_tt, functions=functions)


def _repo_root():
    from pathlib import Path

    return Path(__file__).resolve().parents[1]


def mean_image(items) -> np.ndarray:
    return np.mean([i["image"] for i in items], axis=0)
