"""Comparing one parity scene: build it in an emptied file, render it with Cycles and with Prism, and
measure the difference."""

from __future__ import annotations

from pathlib import Path

import bpy

from . import building
from .engines import render_cycles, render_prism
from .metrics import alpha_difference, luminance_ratio, relative_mse
from .pictures import side_by_side
from .record import ParityResult, ParityScene


def build(scene: ParityScene):
    """The scene built in a fresh, empty file (48 × 48 unless the builder says otherwise)."""
    bpy_scene = building.empty_file()
    scene.build()
    return bpy_scene


def compare(scene: ParityScene, seed: int = 0, picture: Path | None = None, docs: Path | None = None) -> ParityResult:
    """Render ``scene`` with both engines (the same samples, bounce limit and seed) and compare; with
    ``picture``, write the side-by-side PNG there (recorded relative to ``docs``)."""
    bpy_scene = build(scene)
    cycles = render_cycles(bpy_scene, scene.samples, scene.bounces, scene.output, seed)
    prism = render_prism(bpy_scene, scene.samples, scene.bounces, scene.output, seed)
    comparable = prism.rgba is not None and prism.rgba.shape == cycles.rgba.shape
    result = ParityResult(
        scene=scene, prism=prism, cycles=cycles,
        ratio=luminance_ratio(prism.rgba, cycles.rgba) if comparable else None,
        rel_mse=relative_mse(prism.rgba, cycles.rgba) if comparable else None,
        alpha_difference=alpha_difference(prism.rgba, cycles.rgba) if comparable else None,
    )
    if picture is not None:
        side_by_side(prism.rgba, cycles.rgba, picture)
        result.picture = str(picture.relative_to(docs)) if docs is not None else str(picture)
    return result
