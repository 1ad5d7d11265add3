"""``Scene.prism`` → the rendered viewport's settings: the final render's, with the viewport's own
bounces (lower by default: a faster first image), sample target and pause."""

from __future__ import annotations

from dataclasses import dataclass

from ..export.settings import export_settings
from ..tracer.settings import RenderSettings


@dataclass(frozen=True)
class ViewportSettings:
    """``render`` (``RenderSettings``; its samples and border are the viewport's business),
    ``samples`` to stop at (0: until stopped), ``paused``."""

    render: RenderSettings
    samples: int
    paused: bool


def viewport_settings(scene) -> ViewportSettings:
    prism = scene.prism
    render = export_settings(scene)
    render.max_bounces = int(prism.preview_max_bounces)
    return ViewportSettings(render, int(prism.preview_samples), bool(prism.preview_pause))
