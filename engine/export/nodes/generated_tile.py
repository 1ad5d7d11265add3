"""A UDIM tile Blender generates (Image ▸ New with Tiled, or Image ▸ Fill Tile): its pixels worked out from
the tile's generation settings, as Blender fills the tile's buffer, since ``Image.pixels`` gives the first
tile only and no other Python API reads a tile's buffer.

Blender fills a Blank tile with its ``generated_color``: an 8-bit tile stores each channel as the level
⌊255 c + ½⌋ (0 at or below 0, 255 above 1 − ½ / 255), decoded later in the image's colour space like any
8-bit image; a float tile stores the colour taken from sRGB to linear (alpha unchanged), or the colour as
it is in a data colour space (Non-Color). The UV Grid and Color Grid patterns (the latter with letters
drawn by Blender's font renderer) are not reproduced.
"""

from __future__ import annotations

import numpy as np

from .colour_spaces import is_data, srgb_to_linear
from .pixel_source import PixelSource


def _levels(colour):
    """Blender's 8-bit levels of the float ``colour`` (its float32 arithmetic)."""
    colour = np.asarray(colour, np.float32)
    levels = np.floor(np.float32(255.0) * colour + np.float32(0.5))
    return np.where(colour <= 0.0, 0.0, np.where(colour > np.float32(1.0 - 0.5 / 255.0), 255.0, levels))


def tile_colour(tile, colour_space) -> np.ndarray:
    """RGBA that Blender fills the Blank generated ``tile`` with, as ``Image.pixels`` would give it
    (8-bit tiles as levels / 255, float tiles as stored)."""
    colour = np.array(tile.generated_color, np.float32)
    if not tile.use_generated_float:
        return (_levels(colour) / 255.0).astype(np.float32)
    if not is_data(colour_space):
        colour[:3] = srgb_to_linear(np.clip(colour[:3], 0.0, None))
    return colour


def generated_source(tile, name, colour_space, alpha_mode):
    """A ``PixelSource`` for the generated ``tile`` (a ``UDIMTile``), or None for a pattern Prism does not
    draw (UV Grid, Color Grid)."""
    if tile.generated_type != "BLANK":
        return None
    colour = tile_colour(tile, colour_space)
    width, height = tile.generated_width, tile.generated_height

    def fill(out):
        out.reshape(-1, 4)[:] = colour

    return PixelSource(name, width, height, bool(tile.use_generated_float), colour_space, alpha_mode, fill)
