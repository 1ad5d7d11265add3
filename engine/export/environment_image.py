"""A Blender image used as an environment → linear Rec.709 texels, Prism's layout (row 0 at the top).

Float images hold scene-linear values already (Blender converts them when it loads them); byte images
hold their colour space's values: sRGB is decoded, Linear Rec.709 and Non-Color are taken as they are,
any other space is reported and taken as linear.
"""

from __future__ import annotations

import numpy as np

from ..tracer.errors import PrismInputError

_LINEAR_SPACES = {"Linear Rec.709", "Non-Color", "Linear", "Raw"}


def srgb_to_linear(values: np.ndarray) -> np.ndarray:
    """The sRGB transfer function inverted (IEC 61966-2-1)."""
    values = np.asarray(values, np.float32)
    return np.where(values <= 0.04045, values / 12.92, ((values + 0.055) / 1.055) ** 2.4).astype(np.float32)


def image_rgb(image, where: str, warnings) -> np.ndarray:
    """float32 [H, W, 3] of ``image`` (row 0 = top); ``PrismInputError`` naming ``where`` if it has no
    pixels (missing file, unsupported format)."""
    loaded = bool(image.has_data) or _load(image)
    width, height = (int(s) for s in image.size)
    if width < 1 or height < 1 or not loaded:
        path = image.filepath_from_user() if image.source == "FILE" else image.source.lower()
        raise PrismInputError(
            f"{where}: image '{image.name}' has no pixels (file '{path}' missing or unreadable): "
            "open the image again or fix its path (Image ▸ Replace)."
        )
    channels = int(image.channels)
    pixels = np.empty(width * height * channels, np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, channels)[::-1]
    rgb = np.repeat(pixels[..., :1], 3, axis=2) if channels < 3 else pixels[..., :3]
    space = image.colorspace_settings.name
    if not image.is_float:
        if space == "sRGB":
            rgb = srgb_to_linear(rgb)
        elif space not in _LINEAR_SPACES and warnings is not None:
            warnings.append(f"{where}: image '{image.name}' is in colour space '{space}', which Prism does not "
                            "convert; its values are taken as linear Rec.709.")
    return np.ascontiguousarray(rgb, dtype=np.float32)


def _load(image) -> bool:
    try:
        image.pixels[0]  # noqa: B018 - touching the pixels loads them
    except (RuntimeError, IndexError):
        return False
    return bool(image.has_data)
