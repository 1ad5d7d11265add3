"""Blender images → ``TextureImage``: texels read with ``foreach_get``, decoded from the image's colour
space to scene-linear Rec.709 once per render.

Blender keeps float images (EXR, HDR, float generated images) in scene-linear already; 8-bit images hold
the file's levels, decoded here with Blender's own OpenColorIO configuration (every input colour space
Blender offers: sRGB, Non-Color, linear spaces, Filmic/AgX log, display spaces, ACES). A colour space
that maps each channel on its own keeps the image as 8-bit levels plus a 256-entry table per channel (4
bytes a texel, as Cycles stores them); one that mixes channels (AgX, ACES) is decoded to float32.
"""

from __future__ import annotations

import numpy as np

from ...tracer.materials.shader import TextureImage
from ..texture_memory import DECODED, FLOAT, LEVELS, budget_of
from .colour_spaces import level_table, srgb_to_linear, to_linear
from .pixel_source import PixelSource
from .udim import read_udim

MISSING_COLOUR = (1.0, 0.0, 1.0, 1.0)  # Blender's colour for an image it cannot read


def _levels(pixels):
    """The 8-bit levels of ``pixels`` (float32 0-1), worked out in place: no float copy of a large image
    (``export.texture_memory`` counts what reading an image costs)."""
    np.multiply(pixels, 255.0, out=pixels)
    np.rint(pixels, out=pixels)
    np.clip(pixels, 0.0, 255.0, out=pixels)
    return pixels.astype(np.uint8)


def read_image(image, node, warn, cache):
    """The ``TextureImage`` (a ``UdimImage`` for a UDIM image) of ``image`` for Image Texture ``node``
    (shared through ``cache``), or None when it cannot be read (Blender renders such images magenta)."""
    if image is None:
        warn(node, "has no image; Prism renders it magenta, as Blender does.")
        return None
    key = (image.name, image.colorspace_settings.name, image.alpha_mode, node.interpolation, node.extension)
    if key in cache:
        return cache[key]
    if image.source == "TILED":
        result = read_udim(image, node, warn, lambda source: texture_from(source, node, warn, cache))
    else:
        if image.source in ("MOVIE", "SEQUENCE"):
            warn(node, f"uses the {image.source.lower()} '{image.name}'; Prism reads its current frame only.")
        width, height = image.size
        if width == 0 or height == 0:
            warn(node, f"cannot read image '{image.name}' (missing file?); Prism renders it magenta, as Blender does.")
            result = None
        else:
            result = texture_from(PixelSource(image.name, width, height, image.is_float, image.colorspace_settings.name,
                                              image.alpha_mode, image.pixels.foreach_get), node, warn, cache)
    cache[key] = result
    return result


def texture_from(source: PixelSource, node, warn, cache) -> TextureImage:
    """The ``TextureImage`` of ``source`` for Image Texture ``node``, once the render's texture memory
    (``budget_of(cache)``) admits it."""
    width, height, colour_space = source.width, source.height, source.colour_space
    table = None if source.is_float else level_table(colour_space)
    cost = FLOAT if source.is_float else LEVELS if colour_space == "sRGB" or table is not None else DECODED
    budget_of(cache).admit(source.name, node.name, width, height, cost, source.alpha_mode == "PREMUL")
    pixels = np.empty(width * height * 4, np.float32)
    source.fill(pixels)
    pixels = pixels.reshape(height, width, 4)
    if source.alpha_mode == "PREMUL":
        alpha = pixels[..., 3:4]
        pixels[..., :3] = np.where(alpha > 0, pixels[..., :3] / np.where(alpha > 0, alpha, 1.0), pixels[..., :3])
    if source.alpha_mode == "NONE":
        pixels[..., 3] = 1.0
    interpolation = node.interpolation if node.interpolation in ("Closest", "Linear", "Cubic") else "Linear"
    if node.interpolation == "Smart":
        interpolation = "Cubic"
    if source.is_float:
        return TextureImage(source.name, np.ascontiguousarray(pixels), None, interpolation, node.extension)
    if colour_space == "sRGB":  # Blender filters sRGB levels and decodes after
        return TextureImage(source.name, _levels(pixels), None, interpolation, node.extension, srgb_levels=True)
    if table is not None:
        return TextureImage(source.name, _levels(pixels), table, interpolation, node.extension)
    decoded = to_linear(colour_space, pixels[..., :3].reshape(-1, 3))
    if decoded is None:
        warn(node, f"image '{source.name}' is in colour space '{colour_space}', which Prism cannot decode; "
                   "it is read as sRGB.")
        decoded = srgb_to_linear(pixels[..., :3].reshape(-1, 3))
    rgba = np.concatenate([decoded.reshape(height, width, 3), pixels[..., 3:4]], axis=2)
    return TextureImage(source.name, np.ascontiguousarray(rgba, dtype=np.float32), None, interpolation,
                        node.extension)
