"""One F12 or batch render: export, progressive passes, Render Result updates.

Imported only when a render starts (it pulls in the tracer: numpy, embreex,
colour-science).
"""

from __future__ import annotations

import math
import time

import numpy as np

from .export import export_scene
from .export.settings import export_settings
from .tracer.errors import PrismInputError

#: The message of the last render that failed, for the batch script (None if it succeeded).
last_error: str | None = None


class RenderSession:
    """Renders one frame of ``depsgraph`` through ``engine`` (a ``PrismRenderEngine``)."""

    def __init__(self, engine, depsgraph, samples: int | None = None, seed: int | None = None):
        self.engine = engine
        self.depsgraph = depsgraph
        self.samples = samples
        self.seed = seed

    def fail(self, message: str) -> None:
        global last_error
        last_error = message
        self.engine.error_set(message)
        self.engine.report({"ERROR"}, message)

    def run(self) -> None:
        global last_error
        last_error = None
        try:
            self._render()
        except PrismInputError as error:
            self.fail(str(error))

    def _render(self) -> None:
        from .tracer.renderer import Renderer

        engine = self.engine
        scene = self.depsgraph.scene
        engine.update_stats("", "Prism | Exporting scene")
        tracer_scene = export_scene(self.depsgraph)
        settings = export_settings(scene, self.samples, self.seed)
        renderer = Renderer(tracer_scene, settings)
        width, height = tracer_scene.camera.resolution
        passes = math.ceil(settings.samples / settings.samples_per_pass)
        result = engine.begin_result(0, 0, width, height)
        combined = result.layers[0].passes["Combined"]
        started = time.perf_counter()
        try:
            for index in range(passes):
                if engine.test_break():
                    break
                renderer.render_pass()
                combined.rect = _bottom_up_rgba(renderer.image_rgb())
                engine.update_result(result)
                engine.update_progress((index + 1) / passes)
                engine.update_stats("", _stats_line(renderer, index + 1, passes, time.perf_counter() - started))
        finally:
            engine.end_result(result)


def _bottom_up_rgba(image_rgb: np.ndarray) -> np.ndarray:
    """[H, W, 3] with row 0 at the top → Blender's flat [H*W, 4], first row at the bottom."""
    height, width, _ = image_rgb.shape
    rgba = np.ones((height, width, 4), np.float32)
    rgba[..., :3] = image_rgb[::-1]
    return rgba.reshape(-1, 4)


def _stats_line(renderer, pass_index: int, passes: int, seconds: float) -> str:
    stats = renderer.stats
    rays_per_second = stats.get("rays_cast", 0) / seconds if seconds > 0 else 0.0
    parts = [
        f"Prism | Pass {pass_index}/{passes}",
        f"{renderer.samples_done} spp",
        f"{rays_per_second / 1e6:.2f} M rays/s",
        renderer.strategy,
    ]
    if stats.get("nan_samples"):
        parts.append(f"{stats['nan_samples']} NaN samples dropped")
    warnings = stats.get("warnings") or []
    if warnings:
        parts.append(f"{len(warnings)} warning(s): {warnings[0]}")
    return " | ".join(parts)
