"""UDIM images: one texture per tile, each tile's pixels taken from where Blender takes them when Cycles
asks it for the tile (``BKE_image_acquire_ibuf`` per tile), without loading anything into ``bpy.data``
during a render (``Image.pixels`` gives the first tile only):

1. a tile Blender generated (``UDIMTile.is_generated_tile``): from its generation settings;
2. a packed image (Pack Resources, ``Image.pack``): from the bytes packed for the tile, decoded with
   OpenImageIO. Blender uses packed tiles only while the image has one packed file per tile: otherwise
   (a tile added after packing) it drops them the next time it loads a tile and reads the files, and so
   does Prism;
3. otherwise the tile's own file: the image's path with ``<UDIM>`` replaced by the tile's number
   (1001 + u + 10 v) or ``<UVTILE>`` by ``u<u + 1>_v<v + 1>``, as Blender names them.

Every tile is decoded as an ordinary image in the UDIM image's colour space; a tile none of these give
renders magenta, as Cycles renders a missing tile.
"""

from __future__ import annotations

import contextlib
import os
import tempfile

from ...tracer.materials.shader import UdimImage
from ...tracer.textures.image import FIRST_TILE, TILES_PER_ROW
from .generated_tile import generated_source
from .tile_file import file_source, packed_source
from .udim_warnings import UdimWarnings


def tile_path(path: str, number: int) -> str:
    """``path`` with Blender's tile tokens replaced for tile ``number``."""
    u, v = (number - FIRST_TILE) % TILES_PER_ROW, (number - FIRST_TILE) // TILES_PER_ROW
    return path.replace("<UDIM>", str(number)).replace("<UVTILE>", f"u{u + 1}_v{v + 1}")


def packed_tiles(image) -> dict | None:
    """{tile number: ``ImagePackedFile``} Blender reads ``image``'s tiles from, or None when it reads none:
    nothing packed, or not one packed file per tile and view (Blender then drops the packed files)."""
    packed = list(image.packed_files)
    if not packed:
        return None
    views = len({p.view for p in packed})
    if len(packed) != views * len(image.tiles):
        return None
    return {p.tile_number: p for p in packed if p.view == 0}


def _tile_source(tile, image, pattern, packed, folder, notes):
    """The ``PixelSource`` of ``tile``, or None (with the reason noted in ``notes``)."""
    number, colour_space, alpha_mode = tile.number, image.colorspace_settings.name, image.alpha_mode
    name = f"{image.name} tile {number}"
    if tile.is_generated_tile:
        source = generated_source(tile, name, colour_space, alpha_mode)
        if source is None:
            notes.pattern(number, tile.generated_type)
        return source
    if packed is not None:
        if number not in packed or packed[number].packed_file is None:
            notes.unread(number, "nothing packed for it")
            return None
        source = packed_source(packed[number], folder, name, colour_space, alpha_mode)
        if source is None:
            notes.unread(number, "its packed bytes are no image OpenImageIO reads")
        return source
    path = tile_path(pattern, number)
    if not os.path.isfile(path):
        notes.unread(number, "no file on disk, nothing packed or generated for it")
        return None
    source = file_source(path, name, colour_space, alpha_mode)
    if source is None:
        notes.unread(number, "its file is no image OpenImageIO reads")
    return source


def read_udim(image, node, warn, read):
    """The ``UdimImage`` of UDIM ``image`` (``read(PixelSource)`` makes each tile's texture), or None when no
    tile can be read. What Prism cannot render as Cycles does is named in warnings (``UdimWarnings``)."""
    import bpy

    pattern = bpy.path.abspath(image.filepath, library=image.library)
    packed = packed_tiles(image)
    notes = UdimWarnings(image)
    notes.check_image(image, packed)
    tiles = []
    # Packed tiles are copied to files for OpenImageIO; the copies go once their texels are read.
    folder_or_none = tempfile.TemporaryDirectory(prefix="prism_udim_") if packed else contextlib.nullcontext()
    with folder_or_none as folder:
        for tile in sorted(image.tiles, key=lambda t: t.number):
            source = _tile_source(tile, image, pattern, packed, folder, notes)
            if source is not None:
                notes.check_tile(tile.number, source)
                tiles.append((tile.number, read(source)))
    notes.emit(lambda message: warn(node, message))
    return UdimImage(image.name, tiles) if tiles else None
