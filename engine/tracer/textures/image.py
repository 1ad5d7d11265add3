"""Image textures at a hit: Blender's Closest, Linear and Cubic (B-spline) interpolation with Repeat,
Extend, Clip and Mirror extension.

Texels are stored once per render, decoded to scene-linear RGBA float32 (``TextureArrays.texels``, each
image a run of width × height × 4 values, row 0 at the bottom as Blender stores images); an image's row
of ``TextureArrays.images`` holds (first texel value, width, height, interpolation, extension). Texel
centres sit at (i + 0.5) / width, as in Blender.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import kernel

#: ``images`` float64 [I, IMAGE_ROW], ``texels`` float32 [N].
TextureArrays = namedtuple("TextureArrays", "images texels")

I_OFFSET, I_WIDTH, I_HEIGHT, I_INTERPOLATION, I_EXTENSION = range(5)
IMAGE_ROW = 5
INTERPOLATIONS = {"Linear": 0, "Closest": 1, "Cubic": 2, "Smart": 2}
EXTENSIONS = {"REPEAT": 0, "EXTEND": 1, "CLIP": 2, "MIRROR": 3}


def build_textures(images) -> TextureArrays:
    """Arrays for ``images`` (``materials.shader.TextureImage``), in order."""
    rows, chunks, offset = [], [], 0
    for image in images:
        texels = np.ascontiguousarray(image.texels, dtype=np.float32)
        height, width = texels.shape[:2]
        rows.append([offset, width, height, INTERPOLATIONS.get(image.interpolation, 0),
                     EXTENSIONS.get(image.extension, 0)])
        chunks.append(texels.reshape(-1))
        offset += texels.size
    table = np.array(rows, dtype=np.float64).reshape(-1, IMAGE_ROW)
    data = np.concatenate(chunks) if chunks else np.zeros(4, np.float32)
    return TextureArrays(table if len(table) else np.zeros((1, IMAGE_ROW)), data)


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
def _texel(texels, offset, width, x, y, out_weight, acc):
    """Add ``out_weight`` × texel (x, y) to ``acc`` (a 4-tuple); texels at -1 are transparent black."""
    if x < 0 or y < 0 or out_weight == 0.0:
        return acc
    base = offset + (y * width + x) * 4
    return (acc[0] + out_weight * texels[base], acc[1] + out_weight * texels[base + 1],
            acc[2] + out_weight * texels[base + 2], acc[3] + out_weight * texels[base + 3])


@kernel
def _bspline(t):
    w0 = (((-1.0 / 6.0) * t + 0.5) * t - 0.5) * t + 1.0 / 6.0
    w1 = ((0.5 * t - 1.0) * t) * t + 2.0 / 3.0
    w2 = ((-0.5 * t + 0.5) * t + 0.5) * t + 1.0 / 6.0
    return w0, w1, w2, 1.0 / 6.0 * t * t * t


@kernel
def image_lookup(textures, image, s, t):
    """RGBA of image ``image`` at texture coordinates (s, t) (0-1 across the image, (0, 0) bottom left)."""
    row = textures.images[image]
    offset = int(row[I_OFFSET])
    width = int(row[I_WIDTH])
    height = int(row[I_HEIGHT])
    interpolation = int(row[I_INTERPOLATION])
    extension = int(row[I_EXTENSION])
    texels = textures.texels
    acc = (0.0, 0.0, 0.0, 0.0)
    if not (math.isfinite(s) and math.isfinite(t)):
        return acc
    if extension == 2 and (s < 0.0 or s > 1.0 or t < 0.0 or t > 1.0):
        return acc
    x = s * width
    y = t * height
    if interpolation == 1:
        return _texel(texels, offset, width, _index(int(math.floor(x)), width, extension),
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
        acc = _texel(texels, offset, width, x0, y0, (1.0 - tx) * (1.0 - ty), acc)
        acc = _texel(texels, offset, width, x1, y0, tx * (1.0 - ty), acc)
        acc = _texel(texels, offset, width, x0, y1, (1.0 - tx) * ty, acc)
        return _texel(texels, offset, width, x1, y1, tx * ty, acc)
    wx = _bspline(tx)
    wy = _bspline(ty)
    for j in range(4):
        yj = _index(iy - 1 + j, height, extension)
        for i in range(4):
            acc = _texel(texels, offset, width, _index(ix - 1 + i, width, extension), yj, wx[i] * wy[j], acc)
    return acc
