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
