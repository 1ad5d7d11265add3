"""Prism's and Cycles' renders of one scene side by side in a PNG, each captioned with its mean luminance, both
through the same view transform (sRGB of the scene-linear image, clipped), for the pictures in docs/."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _display(rgb):
    rgb = np.clip(rgb, 0.0, 1.0)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)
    return (srgb * 255 + 0.5).astype(np.uint8)


def save_side_by_side(prism, cycles, prism_mean: float, cycles_mean: float, output: Path) -> None:
    """Write ``prism`` | ``cycles`` (scene-linear RGB [H, W, 3], row 0 on top) to ``output``."""
    from PIL import Image, ImageDraw

    height, width = prism.shape[:2]
    canvas = Image.new("RGB", (2 * width + 6, height + 18), (255, 255, 255))
    canvas.paste(Image.fromarray(_display(prism)), (0, 18))
    canvas.paste(Image.fromarray(_display(cycles)), (width + 6, 18))
    draw = ImageDraw.Draw(canvas)
    draw.text((4, 3), f"Prism (mean {prism_mean:.3f})", fill=(0, 0, 0))
    draw.text((width + 10, 3), f"Cycles 4.5 (mean {cycles_mean:.3f})", fill=(0, 0, 0))
    output.parent.mkdir(parents=True, exist_ok=True)
    canvas.save(output)
    print(f"wrote {output}")


def picture_main(description: str, build, output: Path, samples: int, bounces: int) -> None:
    """A picture tool's whole run: ``--samples`` (default ``samples``), the add-on registered in the bpy module,
    ``build(bpy)`` making the scene, Prism and Cycles rendering it with ``bounces``, both means printed and the
    picture written to ``output``."""
    import argparse
    import sys

    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--samples", type=int, default=samples)
    arguments = parser.parse_args()
    root = Path(__file__).resolve().parents[1]
    sys.path[:0] = [str(root), str(root / "tests")]
    import bpy

    from helpers.cycles import configure_cycles, luminance, render_cycles_rgba, render_prism_rgba
    from render import load_addon_package

    load_addon_package().register()
    build(bpy)
    scene = bpy.context.scene
    scene.prism.max_bounces = bounces
    # Prism reads Cycles' Light Paths settings: without this it would render with the factory clamps (Clamp
    # Indirect 10) and Filter Glossy 1 that Cycles is then rendered without.
    configure_cycles(scene, arguments.samples, max_bounces=bounces)
    prism = render_prism_rgba(scene, arguments.samples)[..., :3]
    cycles = render_cycles_rgba(scene, arguments.samples, max_bounces=bounces)[..., :3]
    p, c = float(luminance(prism).mean()), float(luminance(cycles).mean())
    print(f"mean luminance: Prism {p:.4f}, Cycles {c:.4f}, Prism / Cycles {p / c:.4f}", flush=True)
    save_side_by_side(prism, cycles, p, c, output)
    import os

    os._exit(0)  # the bpy module's interpreter exit can hang after renders (seen with these tools)
