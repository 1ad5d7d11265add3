"""Cycles' shadow terminator Geometry Offset in Prism: docs/images/shadow_terminator.png.

    .venv/bin/python tools/shadow_terminator_picture.py [--samples 64]

A white smooth-shaded UV sphere of 12 segments and 6 rings under a sun 80° off the camera's axis, direct light
only (Max Bounces 0), three panels: Prism at Geometry Offset 0 (the facets shadow the band along the terminator
that their interpolated normals still turn to the sun: how Prism rendered every smooth mesh before 2026-12-07),
Prism at Blender's default 0.1, and Cycles 4.5 at 0.1. Prints each panel's mean luminance, absolute.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "shadow_terminator.png"
SIZE = 192


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=64)
    arguments = parser.parse_args()
    sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tools")]
    import bpy
    from PIL import Image, ImageDraw

    from helpers.bpy_scenes import coarse_sphere_under_low_sun
    from helpers.cycles import configure_cycles, luminance, render_cycles_rgba, render_prism_rgba
    from render import load_addon_package
    from side_by_side import _display

    load_addon_package().register()
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    sphere = coarse_sphere_under_low_sun(resolution=(SIZE, SIZE))
    scene = bpy.context.scene
    scene.prism.max_bounces = 0
    configure_cycles(scene, arguments.samples, max_bounces=0)
    panels = []
    for label, offset, render in (("Prism, Geometry Offset 0", 0.0, render_prism_rgba),
                                  ("Prism, 0.1 (default)", 0.1, render_prism_rgba),
                                  ("Cycles 4.5, 0.1", 0.1, lambda s, n: render_cycles_rgba(s, n, max_bounces=0))):
        sphere.shadow_terminator_geometry_offset = offset
        rgb = np.asarray(render(scene, arguments.samples)[..., :3], np.float64)
        mean = float(luminance(rgb).mean())
        print(f"MEASURED {label}: mean luminance {mean:.5f}", flush=True)
        panels.append((f"{label}: {mean:.4f}", rgb))
    canvas = Image.new("RGB", (3 * SIZE + 12, SIZE + 18), (255, 255, 255))
    draw = ImageDraw.Draw(canvas)
    for k, (caption, rgb) in enumerate(panels):
        canvas.paste(Image.fromarray(_display(rgb)), (k * (SIZE + 6), 18))
        draw.text((k * (SIZE + 6) + 4, 3), caption, fill=(0, 0, 0))
    OUTPUT.parent.mkdir(parents=True, exist_ok=True)
    canvas.save(OUTPUT)
    print(f"wrote {OUTPUT}", flush=True)
    os._exit(0)  # the bpy module's interpreter exit can hang after renders (seen with these tools)


if __name__ == "__main__":
    main()
