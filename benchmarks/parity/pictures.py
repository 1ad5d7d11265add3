"""Side-by-side pictures (Prism | Cycles) for the report: small sRGB PNGs, enlarged by whole pixels so
the noise of a tiny render stays visible as noise."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image

GAP_PX = 2  # a white seam between the two images
SCALE = 2  # each rendered pixel becomes SCALE × SCALE


def _srgb(linear: np.ndarray) -> np.ndarray:
    """Linear RGB → 8-bit sRGB (the standard transfer curve, clipped; no view transform or look: the
    picture shows both engines' pixels the same way, not as Blender's AgX would)."""
    x = np.clip(linear, 0.0, 1.0)
    encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return np.round(encoded * 255.0).astype(np.uint8)


def _over_checker(rgba: np.ndarray) -> np.ndarray:
    """Premultiplied RGBA composited over a grey checkerboard, so transparency shows."""
    height, width = rgba.shape[:2]
    rows, columns = np.mgrid[0:height, 0:width]
    checker = np.where((rows // 4 + columns // 4) % 2, 0.18, 0.35)[..., None]
    alpha = np.clip(rgba[..., 3:4], 0.0, 1.0)
    return rgba[..., :3] + (1.0 - alpha) * checker


def side_by_side(prism: np.ndarray | None, cycles: np.ndarray, path: Path) -> None:
    """Write Prism's image (black with a red cross where it refused) beside Cycles' to ``path``."""
    right = _over_checker(cycles)
    if prism is None or prism.shape != cycles.shape:
        left = np.zeros_like(right)
        diagonal = np.linspace(0, 1, max(right.shape[:2]))
        for t in diagonal:  # a cross: no image, or one of another size
            y, x = int(t * (right.shape[0] - 1)), int(t * (right.shape[1] - 1))
            left[y, x] = left[y, right.shape[1] - 1 - x] = (0.8, 0.05, 0.05)
    else:
        left = _over_checker(prism)
    seam = np.ones((right.shape[0], GAP_PX, 3))
    picture = _srgb(np.concatenate([left, seam, right], axis=1))
    picture = picture.repeat(SCALE, axis=0).repeat(SCALE, axis=1)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(picture).save(path, optimize=True)
