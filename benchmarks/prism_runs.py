"""Running Prism's Renderer for the harness: progressive error-vs-time curves.

Time of a checkpoint = Renderer construction (scene analysis, BVH build) + the
render passes so far, excluding the time to read the image back. Passes are
``PASS_SPP`` samples per pixel (fewer when a checkpoint is closer), so a 64 x 64
pass is 65,536 paths, cut into chunks by ``chunk_pool.chunk_size`` (``CHUNKS_PER_THREAD`` per thread).
"""

from __future__ import annotations

import time
from dataclasses import replace

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
    return _checkpoints(scene, settings, sorted(set(int(c) for c in checkpoints)), float("inf"), on_renderer)


def progressive_until(scene, settings: RenderSettings, first_spp: int, seconds: float, max_spp: int):
    """Like ``progressive`` with checkpoints doubling from ``first_spp`` until the render has taken
    ``seconds`` (or reached ``max_spp``)."""
    spp = [int(first_spp)]
    while spp[-1] * 2 <= max_spp:
        spp.append(spp[-1] * 2)
    return _checkpoints(scene, settings, spp, seconds)


def _checkpoints(scene, settings, checkpoints, seconds, on_renderer=None):
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
                t0 = time.perf_counter()
                renderer.render_pass(min(PASS_SPP, target - renderer.samples_done))
                elapsed += time.perf_counter() - t0
            out.append(dict(spp=renderer.samples_done, seconds=elapsed, setup=setup, image=renderer.image_rgb(),
                            rays_cast=int(renderer.stats["rays_cast"])))
            if elapsed >= seconds:
                break
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
