"""The lens overlay's colours: a wavelength's display colour and the RGBA of the lens outline, stop,
sensor, axis, text and spot inset, shared by the viewport drawing (``lens_overlay_draw``), the spot
inset (``lens_spot_inset``) and the PNG export (``lens_overlay_export``).
"""

from __future__ import annotations

import functools

BLOCKED_ALPHA = 0.25
OUTLINE_RGBA = (0.62, 0.78, 0.95, 0.9)
STOP_RGBA = (0.95, 0.95, 0.95, 0.95)
SENSOR_RGBA = (0.75, 0.75, 0.75, 0.9)
AXIS_RGBA = (0.5, 0.5, 0.5, 0.5)
TEXT_RGBA = (0.92, 0.92, 0.92, 1.0)
SPOT_BACKGROUND_RGBA = (0.04, 0.04, 0.05, 0.8)
SPOT_POINT_SIZE = 3.0


def display_colours(wavelengths_nm):
    """Display (sRGB-encoded) RGB per wavelength: the CIE colour of the monochromatic light,
    scene-linear Rec.709 with its largest channel 1, through the sRGB transfer function."""
    return [_display_colour(float(w)) for w in wavelengths_nm]


@functools.lru_cache(maxsize=256)
def _display_colour(wavelength_nm):
    import numpy as np

    from ..engine.tracer.spectra.cie import monochromatic_rgb

    linear = np.clip(np.asarray(monochromatic_rgb(np.array([wavelength_nm])), dtype=np.float64)[0], 0.0, 1.0)
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1.0 / 2.4) - 0.055)
    return tuple(float(c) for c in encoded)
