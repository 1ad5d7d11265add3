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


def _luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def replace_bad_texels(rgb: np.ndarray, where: str, image_name: str, warnings) -> np.ndarray:
    """``rgb`` with NaN, infinite and negative values replaced by 0, which is what Prism renders for them; a
    warning counts them and says how much light the negative ones hold (Cycles subtracts it, Prism does
    not), measured by solid angle over the sphere."""
    finite = np.isfinite(rgb)
    negative = finite & (rgb < 0)
    if finite.all() and not negative.any():
        return rgb
    nan_texels = int(np.isnan(rgb).any(axis=2).sum())
    infinite_texels = int((np.isinf(rgb) & ~np.isnan(rgb)).any(axis=2).sum())
    negative_texels = int(negative.any(axis=2).sum())
    whole = finite.all(axis=2, keepdims=True)  # a NaN or infinite channel blackens its texel
    cleaned = np.where(whole & ~negative, rgb, 0.0).astype(np.float32)
    counts = [f"{count} {what}" for count, what in ((nan_texels, "NaN"), (infinite_texels, "infinite"),
                                                    (negative_texels, "negative")) if count]
    counted = ", ".join(counts[:-1]) + (" and " if len(counts) > 1 else "") + counts[-1]
    message = (f"{where}: image '{image_name}' has {counted} texels (of {rgb.shape[0] * rgb.shape[1]}); Prism renders "
               "NaN and infinite texels black and negative values as 0.")
    if negative_texels:
        height = rgb.shape[0]
        solid_angle = np.sin((np.arange(height) + 0.5) / height * np.pi)[:, None]  # equirectangular rows
        light = float((solid_angle * _luminance(cleaned.astype(np.float64))).sum())
        taken = -float((solid_angle * _luminance(np.where(negative, rgb, 0.0).astype(np.float64))).sum())
        if light > taken > 0:
            message += (f" The negative values would take {100 * taken / light:.2g} % of the image's light away "
                        f"(Cycles subtracts it): Prism's world emits {100 * taken / (light - taken):.2g} % more.")
        elif taken > 0:
            message += " The negative values outweigh the positive ones (Cycles' world would be black or negative)."
    if warnings is not None:
        warnings.append(message + " Clamp the image at 0 and replace its NaN and infinite texels to match Cycles.")
    return cleaned
