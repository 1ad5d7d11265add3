"""What an image texture's texels are read from: a Blender image or a UDIM tile's file."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PixelSource:
    """An image's pixels as Blender's ``Image.pixels`` gives them (float32 RGBA, row 0 at the bottom, 8-bit
    images as levels / 255, float ones as stored), with what decoding them needs; ``fill(out)`` writes
    them into a flat float32 array of ``width * height * 4``."""

    name: str
    width: int
    height: int
    is_float: bool
    colour_space: str
    alpha_mode: str
    fill: Callable[[np.ndarray], None]
