"""The range of light values Prism renders: what float32 (the film, the kernels' radiance) can carry.

A radiance, power or strength above ``LARGEST`` overflows to infinity somewhere along a path (BSDF over
pdf, the colour-matching weights, thousands of samples summed): a white or NaN frame. A positive one
below ``SMALLEST`` becomes 0 in float32: a black light that looks switched on. Both are refused at export,
naming the object, the setting and the value, before any numpy arithmetic could warn about them.
"""

from __future__ import annotations

import math

from ..tracer.errors import PrismInputError

#: The brightest value Prism renders (float32's largest is 3.4e38: 18 decades are left for the path).
LARGEST = 1e20
#: The dimmest positive value Prism renders (float32's smallest normal number is 1.2e-38).
SMALLEST = 1e-30


def check_light_value(value: float, where: str, setting: str, unit: str = "") -> None:
    """``PrismInputError`` when ``value`` (finite, not negative: checked by the caller's own message) is
    too large or too small but positive for float32; ``where`` names the object, ``setting`` the setting."""
    value = float(value)
    if not math.isfinite(value) or value > LARGEST:
        raise PrismInputError(
            f"{where}: {setting} is {value:.3g}{unit}; Prism renders light values up to {LARGEST:g} (float32 overflows "
            "beyond, a white or black frame): lower it."
        )
    if 0.0 < value < SMALLEST:
        raise PrismInputError(
            f"{where}: {setting} is {value:.3g}{unit}, below {SMALLEST:g}, which float32 renders as 0 (a black light "
            f"that looks on): set it to 0 for no light, or to {SMALLEST:g} or more."
        )
