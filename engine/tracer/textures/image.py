"""Image textures at a hit: Blender's Closest, Linear and Cubic (B-spline) interpolation with Repeat,
Extend, Clip and Mirror extension.

Texels are stored once per render, row 0 at the bottom as Blender stores images, each image a run of
width × height × 4 values: 8-bit images as they are (``bytes``) with a table decoding each channel's 256
levels to scene-linear (``decode``, the image's colour space) — 8-bit sRGB images are filtered as levels
and decoded after (as Blender does) — others decoded to scene-linear float32 (``floats``). An image's row of ``TextureArrays.images`` holds (first value, width, height,
interpolation, extension, decode table or -1, tile). Texel centres sit at (i + 0.5) / width, as in Blender.

A UDIM image is a header row (``I_TILE`` = minus its tile count) followed by one row per tile (``I_TILE`` = the
tile's number, 1001 + u + 10 v). As Cycles does, a lookup at (s, t) truncates them to the tile
(u, v) = (int(s), int(t)), reads that tile at (s - u, t - v), and renders a tile the image lacks (or u outside
0-9, v below 0) magenta.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined, kernel

#: ``images`` float64 [I, IMAGE_ROW], ``floats`` float32 [N], ``bytes`` uint8 [M], ``decode`` float32 [D, 256, 3].
TextureArrays = namedtuple("TextureArrays", "images floats bytes decode")

I_OFFSET, I_WIDTH, I_HEIGHT, I_INTERPOLATION, I_EXTENSION, I_DECODE, I_TILE = range(7)
IMAGE_ROW = 7
FIRST_TILE = 1001  # UDIM numbering: tile (u, v) is 1001 + u + 10 v
TILES_PER_ROW = 10
MISSING_RGBA = (1.0, 0.0, 1.0, 1.0)  # what Blender and Cycles render for an image or tile they cannot read
SRGB_LEVELS = -2  # ``I_DECODE`` of 8-bit sRGB images: levels filtered first, then decoded (as Blender does)
INTERPOLATIONS = {"Linear": 0, "Closest": 1, "Cubic": 2, "Smart": 2}
EXTENSIONS = {"REPEAT": 0, "EXTEND": 1, "CLIP": 2, "MIRROR": 3}


def build_textures(images) -> TextureArrays:
    """Arrays for ``images`` (``materials.shader.TextureImage`` or ``UdimImage``), in order: an image's first
    row is the sum of the ``rows`` of the images before it."""
    rows, floats, byte_chunks, decode = [], [], [], []
    offsets = [0, 0]  # next float, next byte

    def add(image, tile):
        height, width = image.texels.shape[:2]
        kind = [INTERPOLATIONS.get(image.interpolation, 0), EXTENSIONS.get(image.extension, 0)]
        if image.decode is not None or image.srgb_levels:
            texels = np.ascontiguousarray(image.texels, dtype=np.uint8).reshape(-1)
            rows.append([offsets[1], width, height, *kind, SRGB_LEVELS if image.srgb_levels else len(decode), tile])
            if not image.srgb_levels:
                decode.append(np.asarray(image.decode, dtype=np.float32).reshape(256, 3))
            byte_chunks.append(texels)
            offsets[1] += texels.size
        else:
            texels = np.ascontiguousarray(image.texels, dtype=np.float32).reshape(-1)
            rows.append([offsets[0], width, height, *kind, -1, tile])
            floats.append(texels)
            offsets[0] += texels.size

    for image in images:
        tiles = getattr(image, "tiles", None)
        if tiles is None:
            add(image, 0)
            continue
        rows.append([0, 0, 0, 0, 0, -1, -len(tiles)])
        for number, tile in tiles:
            add(tile, number)
    table = np.array(rows, dtype=np.float64).reshape(-1, IMAGE_ROW)
    return TextureArrays(table if len(table) else np.zeros((1, IMAGE_ROW)),
                         np.concatenate(floats) if floats else np.zeros(4, np.float32),
                         np.concatenate(byte_chunks) if byte_chunks else np.zeros(4, np.uint8),
                         np.stack(decode) if decode else np.zeros((1, 256, 3), np.float32))


@kernel
def _index(i, size, extension):
    """The texel index for integer coordinate ``i`` along an axis of ``size`` texels, or -1 (clipped)."""
    if extension == 0:
        i = i % size
        return i + size if i < 0 else i
    if extension == 1:
        return min(max(i, 0), size - 1)
    if extension == 2:
        return i if 0 <= i < size else -1
    period = 2 * size
    i = i % period
    if i < 0:
        i += period
    return i if i < size else period - 1 - i


@kernel
def _srgb_to_linear(v):
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


@kernel
def _texel(textures, decode, offset, width, x, y, out_weight, acc):
    """Add ``out_weight`` × texel (x, y) to ``acc`` (a 4-tuple); texels at -1 are transparent black."""
    if x < 0 or y < 0 or out_weight == 0.0:
        return acc
    base = offset + (y * width + x) * 4
    if decode == SRGB_LEVELS:
        texels = textures.bytes
        return (acc[0] + out_weight * texels[base] / 255.0, acc[1] + out_weight * texels[base + 1] / 255.0,
                acc[2] + out_weight * texels[base + 2] / 255.0, acc[3] + out_weight * texels[base + 3] / 255.0)
    if decode >= 0:
        texels = textures.bytes
        table = textures.decode[decode]
        return (acc[0] + out_weight * table[texels[base], 0], acc[1] + out_weight * table[texels[base + 1], 1],
                acc[2] + out_weight * table[texels[base + 2], 2], acc[3] + out_weight * texels[base + 3] / 255.0)
    texels = textures.floats
    return (acc[0] + out_weight * texels[base], acc[1] + out_weight * texels[base + 1],
            acc[2] + out_weight * texels[base + 2], acc[3] + out_weight * texels[base + 3])


@kernel
def _bspline(t):
    w0 = (((-1.0 / 6.0) * t + 0.5) * t - 0.5) * t + 1.0 / 6.0
    w1 = ((0.5 * t - 1.0) * t) * t + 2.0 / 3.0
    w2 = ((-0.5 * t + 0.5) * t + 0.5) * t + 1.0 / 6.0
    return w0, w1, w2, 1.0 / 6.0 * t * t * t


@kernel
def _udim_tile(images, header, s, t):
    """(row, s, t) of the UDIM tile at (s, t) of the UDIM image whose header row is ``header``, the
    coordinates made relative to that tile; row -1 where the image has no such tile."""
    if not (math.isfinite(s) and math.isfinite(t)):
        return -1, s, t
    u = int(s)  # truncated toward zero, as Cycles does: (-0.5, 0.2) reads tile 1001
    v = int(t)
    if u < 0 or v < 0 or u >= TILES_PER_ROW:
        return -1, s, t
    number = FIRST_TILE + u + TILES_PER_ROW * v
    for k in range(1, 1 - int(images[header, I_TILE])):
        if int(images[header + k, I_TILE]) == number:
            return header + k, s - u, t - v
    return -1, s, t


@inlined
def image_lookup(textures, image, s, t):
    """RGBA of image ``image`` at texture coordinates (s, t) (0-1 across the image, (0, 0) bottom left; a
    UDIM image's tiles side by side from (0, 0))."""
    if textures.images[image, I_TILE] < 0.0:
        image, s, t = _udim_tile(textures.images, image, s, t)
        if image < 0:
            return MISSING_RGBA
    rgba = _filtered(textures, image, s, t)
    if int(textures.images[image, I_DECODE]) != SRGB_LEVELS:
        return rgba
    return (_srgb_to_linear(rgba[0]), _srgb_to_linear(rgba[1]), _srgb_to_linear(rgba[2]), rgba[3])


@inlined
def _filtered(textures, image, s, t):
    row = textures.images[image]
    offset = int(row[I_OFFSET])
    width = int(row[I_WIDTH])
    height = int(row[I_HEIGHT])
    interpolation = int(row[I_INTERPOLATION])
    extension = int(row[I_EXTENSION])
    decode = int(row[I_DECODE])
    acc = (0.0, 0.0, 0.0, 0.0)
    if not (math.isfinite(s) and math.isfinite(t)):
        return acc
    if extension == 2 and (s < 0.0 or s > 1.0 or t < 0.0 or t > 1.0):
        return acc
    x = s * width
    y = t * height
    if interpolation == 1:
        return _texel(textures, decode, offset, width, _index(int(math.floor(x)), width, extension),
                      _index(int(math.floor(y)), height, extension), 1.0, acc)
    x -= 0.5
    y -= 0.5
    fx = math.floor(x)
    fy = math.floor(y)
    ix = int(fx)
    iy = int(fy)
    tx = x - fx
    ty = y - fy
    if interpolation == 0:
        x0 = _index(ix, width, extension)
        x1 = _index(ix + 1, width, extension)
        y0 = _index(iy, height, extension)
        y1 = _index(iy + 1, height, extension)
        acc = _texel(textures, decode, offset, width, x0, y0, (1.0 - tx) * (1.0 - ty), acc)
        acc = _texel(textures, decode, offset, width, x1, y0, tx * (1.0 - ty), acc)
        acc = _texel(textures, decode, offset, width, x0, y1, (1.0 - tx) * ty, acc)
        return _texel(textures, decode, offset, width, x1, y1, tx * ty, acc)
    wx = _bspline(tx)
    wy = _bspline(ty)
    for j in range(4):
        yj = _index(iy - 1 + j, height, extension)
        for i in range(4):
            acc = _texel(textures, decode, offset, width, _index(ix - 1 + i, width, extension), yj, wx[i] * wy[j], acc)
    return acc
