"""Blender's colour spaces, decoded to scene-linear Rec.709 with Blender's own OpenColorIO configuration
(every input colour space Blender offers: sRGB, Non-Color, linear spaces, Filmic/AgX log, display spaces,
ACES), or with the sRGB formula where PyOpenColorIO cannot be loaded."""

from __future__ import annotations

import os
import sys

import numpy as np

#: Colour spaces whose levels are the values themselves.
RAW_SPACES = {"Non-Color", "Raw", "Linear Rec.709", "Linear", "Linear CIE-XYZ E"}

_CONFIG: dict = {}


def ocio_config():
    """Blender's OpenColorIO configuration (PyOpenColorIO ships with Blender), or None."""
    if "config" in _CONFIG:
        return _CONFIG["config"]
    config = None
    try:
        import bpy

        local = bpy.utils.resource_path("LOCAL")
        try:
            import PyOpenColorIO as ocio
        except ImportError:
            version = f"python{sys.version_info.major}.{sys.version_info.minor}"
            for site in (os.path.join(local, "python", "lib", version, "site-packages"),
                         os.path.join(local, "python", "lib", "site-packages")):
                if os.path.isdir(site) and site not in sys.path:
                    sys.path.append(site)
            import PyOpenColorIO as ocio
        path = os.environ.get("OCIO") or os.path.join(local, "datafiles", "colormanagement", "config.ocio")
        config = (ocio, ocio.Config.CreateFromFile(path))
    except Exception:  # noqa: BLE001 - decoding falls back to the sRGB formula
        config = None
    _CONFIG["config"] = config
    return config


def srgb_to_linear(v):
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def to_linear(colour_space, rgb):
    """Scene-linear values of ``rgb`` (float32 [N, 3]) in ``colour_space``; None if it cannot be decoded."""
    if colour_space in RAW_SPACES:
        return rgb
    config = ocio_config()
    if config is None:
        return srgb_to_linear(rgb) if colour_space == "sRGB" else None
    ocio, cfg = config
    try:
        processor = cfg.getProcessor(colour_space, "scene_linear").getDefaultCPUProcessor()
    except Exception:  # noqa: BLE001 - an unknown colour space name
        return None
    out = np.ascontiguousarray(rgb, dtype=np.float32).copy()
    processor.applyRGB(out)
    return out


def level_table(colour_space):
    """float32 [256, 3] decoding each channel's levels, or None when the space mixes channels."""
    levels = np.arange(256, dtype=np.float32) / 255.0
    grey = to_linear(colour_space, np.repeat(levels[:, None], 3, axis=1))
    if grey is None:
        return None
    for channel in range(3):
        alone = np.zeros((256, 3), np.float32)
        alone[:, channel] = levels
        decoded = to_linear(colour_space, alone)
        others = np.delete(decoded, channel, axis=1)
        if not (np.allclose(others, others[:1], atol=1e-6) and np.allclose(decoded[:, channel], grey[:, channel],
                                                                           atol=1e-5)):
            return None
    return grey.astype(np.float32)


def is_data(colour_space):
    """Whether ``colour_space`` holds data rather than colour (Non-Color and its aliases), as Blender's
    OpenColorIO configuration marks it."""
    config = ocio_config()
    if config is not None:
        try:
            return bool(config[1].getColorSpace(colour_space).isData())
        except Exception:  # noqa: BLE001 - an unknown colour space name
            return False
    return colour_space in ("Non-Color", "Raw")
