"""UDIM images: one texture per tile, each read from the tile's own file with OpenImageIO (the library
Blender bundles), since ``Image.pixels`` gives the first tile only and loading each tile as a Blender image
would change ``bpy.data`` during a render.

A tile's file is the image's path with ``<UDIM>`` replaced by the tile's number (1001 + u + 10 v) or
``<UVTILE>`` by ``u<u + 1>_v<v + 1>``, as Blender names them. Its pixels are handed on as Blender's
``Image.pixels`` gives them (row 0 at the bottom; 8-bit files as levels / 255 with straight alpha; float
files as stored), so each tile is decoded exactly as an ordinary image in the UDIM image's colour space.
"""

from __future__ import annotations

import os

import numpy as np

from ...output.openimageio import import_openimageio
from ...tracer.materials.shader import UdimImage
from ...tracer.textures.image import FIRST_TILE, TILES_PER_ROW
from .pixel_source import PixelSource

_FLOAT_FORMATS = ("half", "float", "double")


def tile_path(path: str, number: int) -> str:
    """``path`` with Blender's tile tokens replaced for tile ``number``."""
    u, v = (number - FIRST_TILE) % TILES_PER_ROW, (number - FIRST_TILE) // TILES_PER_ROW
    return path.replace("<UDIM>", str(number)).replace("<UVTILE>", f"u{u + 1}_v{v + 1}")


def _tile_source(path, name, colour_space, alpha_mode):
    """A ``PixelSource`` for the tile file at ``path``, or None when OpenImageIO cannot open it."""
    oiio = import_openimageio()
    config = oiio.ImageSpec()
    config.attribute("oiio:UnassociatedAlpha", 1)  # straight alpha, as Blender keeps 8-bit images
    reader = oiio.ImageInput.open(path, config)
    if reader is None:
        return None
    spec = reader.spec()
    width, height, channels = spec.width, spec.height, spec.nchannels
    is_float = str(spec.format) in _FLOAT_FORMATS

    def fill(out):
        try:
            pixels = reader.read_image(0, 0, 0, min(channels, 4), "float")
        finally:
            reader.close()
        if pixels is None:
            raise OSError(f"OpenImageIO could not read '{path}'")
        pixels = np.asarray(pixels, np.float32).reshape(height, width, -1)[::-1]  # files store the top row first
        rgba = out.reshape(height, width, 4)
        if pixels.shape[2] < 3:  # grey, or grey and alpha
            rgba[..., :3] = pixels[..., :1]
            rgba[..., 3] = pixels[..., 1] if pixels.shape[2] == 2 else 1.0
        else:
            rgba[..., :3] = pixels[..., :3]
            rgba[..., 3] = pixels[..., 3] if pixels.shape[2] == 4 else 1.0

    return PixelSource(name, width, height, is_float, colour_space, alpha_mode, fill)


def read_udim(image, node, warn, read):
    """The ``UdimImage`` of UDIM ``image`` (``read(PixelSource)`` makes each tile's texture), or None when no
    tile can be read. Tiles that cannot be read (packed or generated in Blender, missing files) render
    magenta, as Cycles renders a missing tile; the warning names them."""
    import bpy

    pattern = bpy.path.abspath(image.filepath, library=image.library)
    tiles, unread = [], []
    for number in sorted(tile.number for tile in image.tiles):
        path = tile_path(pattern, number)
        source = _tile_source(path, f"{image.name} tile {number}", image.colorspace_settings.name,
                              image.alpha_mode) if os.path.isfile(path) else None
        if source is None:
            unread.append(number)
        else:
            tiles.append((number, read(source)))
    if unread:
        listed = ", ".join(str(n) for n in unread)
        why = "packed in the .blend" if len(image.packed_files) else "no file on disk"
        warn(node, f"cannot read tile{'s' if len(unread) > 1 else ''} {listed} of the UDIM image '{image.name}' "
                   f"({why}: Prism reads each tile's own file); Prism renders {'them' if len(unread) > 1 else 'it'} "
                   "magenta, as Cycles renders a missing tile.")
    return UdimImage(image.name, tiles) if tiles else None
