"""Shared by this issue's experiments: render a benchmark scene to its end and a converged reference."""

from __future__ import annotations

import time

from benchmarks import scenes
from benchmarks.prism_runs import settings_for
from engine.tracer.renderer import Renderer


def render(scene, overrides: dict, samples: int, seed: int = 0, threads: int = 2):
    """(image, pass images, seconds of sampling, film sample counts) of a render run to its end."""
    with Renderer(scene, settings_for(overrides, samples, seed, threads)) as renderer:
        started = time.perf_counter()
        while not renderer.finished:
            renderer.render_pass()
        seconds = time.perf_counter() - started
        return (renderer.image_rgb().astype("float64"), renderer.pass_images(), seconds,
                renderer.film.counts.copy(), renderer.variance_rgb().astype("float64"))


def reference(name: str, resolution: int, samples: int):
    """(image, variance of the mean) of ``name`` at ``samples`` spp (seed 1: independent of the tests)."""
    image, _, _, _, variance = render(scenes.build(name, (resolution, resolution)), {"samples_per_pass": 64},
                                      samples, seed=1)
    return image, variance
