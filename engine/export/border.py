"""The render border (Blender's Render Region) as a pixel rectangle."""

from __future__ import annotations

import numpy as np

from ..tracer.errors import PrismInputError


def render_border(scene, width: int, height: int) -> tuple[int, int, int, int] | None:
    """The render border as pixels (x0, y0, x1, y1), rows from the TOP, half-open; None if off.

    Blender truncates border fractions times the resolution in float32; so do we,
    so the region matches the Render Result Blender allocates.
    """
    render = scene.render
    if not render.use_border:
        return None
    f32 = np.float32
    x0 = int(f32(render.border_min_x) * f32(width))
    x1 = int(f32(render.border_max_x) * f32(width))
    y0_bottom = int(f32(render.border_min_y) * f32(height))
    y1_bottom = int(f32(render.border_max_y) * f32(height))
    if (x0, y0_bottom, x1, y1_bottom) == (0, 0, width, height):
        return None
    if x1 <= x0 or y1_bottom <= y0_bottom:
        raise PrismInputError(
            f"Scene '{scene.name}': the render border is empty: draw a larger border (Ctrl+B) or turn it off."
        )
    return (x0, height - y1_bottom, x1, height - y0_bottom)
