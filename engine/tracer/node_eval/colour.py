"""Blender's colour nodes as scalar kernel code: Mix Color blend modes, HSV/HSL conversions,
Hue/Saturation/Value, Bright/Contrast, Invert, Gamma, RGB to BW, Color Ramp and curve lookups.

Colours are 3-tuples of scene-linear Rec.709 values; blend modes are indices into
``materials.opcodes.BLEND_MODES`` and behave as Blender documents them (Mix, Darken, Multiply, Burn,
Lighten, Screen, Dodge, Add, Overlay, Soft Light, Linear Light, Difference, Exclusion, Subtract, Divide,
Hue, Saturation, Color, Value).
"""

from __future__ import annotations

import math

from ..jit import kernel

#: Luminance weights of linear Rec.709 (the Y row of its RGB → XYZ matrix).
LUMINANCE = (0.2126729, 0.7151522, 0.0721750)


@kernel
def luminance(c):
    return LUMINANCE[0] * c[0] + LUMINANCE[1] * c[1] + LUMINANCE[2] * c[2]


@kernel
def rgb_to_hsv(c):
    largest = max(c[0], c[1], c[2])
    smallest = min(c[0], c[1], c[2])
    delta = largest - smallest
    s = delta / largest if largest != 0.0 else 0.0
    h = 0.0
    if s != 0.0:
        if c[0] == largest:
            h = (c[1] - c[2]) / delta
        elif c[1] == largest:
            h = 2.0 + (c[2] - c[0]) / delta
        else:
            h = 4.0 + (c[0] - c[1]) / delta
        h /= 6.0
        if h < 0.0:
            h += 1.0
    return (h, s, largest)


@kernel
def hsv_to_rgb(hsv):
    h, s, v = hsv
    if s == 0.0:
        return (v, v, v)
    if h == 1.0:
        h = 0.0
    h *= 6.0
    sector = math.floor(h)
    f = h - sector
    p = v * (1.0 - s)
    q = v * (1.0 - s * f)
    t = v * (1.0 - s * (1.0 - f))
    if sector == 0.0:
        return (v, t, p)
    if sector == 1.0:
        return (q, v, p)
    if sector == 2.0:
        return (p, v, t)
    if sector == 3.0:
        return (p, q, v)
    if sector == 4.0:
        return (t, p, v)
    return (v, p, q)


@kernel
def rgb_to_hsl(c):
    largest = max(c[0], c[1], c[2])
    smallest = min(c[0], c[1], c[2])
    lightness = min(1.0, (largest + smallest) / 2.0)
    if largest == smallest:
        return (0.0, 0.0, lightness)
    delta = largest - smallest
    s = delta / (2.0 - largest - smallest) if lightness > 0.5 else delta / (largest + smallest)
    if largest == c[0]:
        h = (c[1] - c[2]) / delta + (6.0 if c[1] < c[2] else 0.0)
    elif largest == c[1]:
        h = (c[2] - c[0]) / delta + 2.0
    else:
        h = (c[0] - c[1]) / delta + 4.0
    return (h / 6.0, s, lightness)


@kernel
def hsl_to_rgb(hsl):
    h, s, lightness = hsl
    r = min(max(abs(h * 6.0 - 3.0) - 1.0, 0.0), 1.0)
    g = min(max(2.0 - abs(h * 6.0 - 2.0), 0.0), 1.0)
    b = min(max(2.0 - abs(h * 6.0 - 4.0), 0.0), 1.0)
    chroma = (1.0 - abs(2.0 * lightness - 1.0)) * s
    return ((r - 0.5) * chroma + lightness, (g - 0.5) * chroma + lightness, (b - 0.5) * chroma + lightness)


@kernel
def _lerp(a, b, t):
    return (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]))


@kernel
def _dodge(a, b, t):
    if a == 0.0:
        return a
    d = 1.0 - t * b
    if d <= 0.0:
        return 1.0
    return min(a / d, 1.0)


@kernel
def _burn(a, b, t):
    d = 1.0 - t + t * b
    if d <= 0.0:
        return 0.0
    return min(max(1.0 - (1.0 - a) / d, 0.0), 1.0)


@kernel
def _overlay(a, b, t):
    if a < 0.5:
        return a * (1.0 - t + 2.0 * t * b)
    return 1.0 - (1.0 - t + 2.0 * t * (1.0 - b)) * (1.0 - a)


@kernel
def _soft_light(a, b, t):
    screen = 1.0 - (1.0 - b) * (1.0 - a)
    return (1.0 - t) * a + t * ((1.0 - a) * b * a + a * screen)


@kernel
def _divide(a, b, t):
    return (1.0 - t) * a + t * a / b if b != 0.0 else a


@kernel
def blend(mode, t, a, b):
    """Blender's Mix Color node: colour ``a`` blended with ``b`` by factor ``t``."""
    if mode == 0:
        return _lerp(a, b, t)
    if mode == 1:
        return _lerp(a, (min(a[0], b[0]), min(a[1], b[1]), min(a[2], b[2])), t)
    if mode == 2:
        return _lerp(a, (a[0] * b[0], a[1] * b[1], a[2] * b[2]), t)
    if mode == 3:
        return (_burn(a[0], b[0], t), _burn(a[1], b[1], t), _burn(a[2], b[2], t))
    if mode == 4:
        return _lerp(a, (max(a[0], b[0]), max(a[1], b[1]), max(a[2], b[2])), t)
    if mode == 5:
        m = 1.0 - t
        return (1.0 - (m + t * (1.0 - b[0])) * (1.0 - a[0]), 1.0 - (m + t * (1.0 - b[1])) * (1.0 - a[1]),
                1.0 - (m + t * (1.0 - b[2])) * (1.0 - a[2]))
    if mode == 6:
        return (_dodge(a[0], b[0], t), _dodge(a[1], b[1], t), _dodge(a[2], b[2], t))
    if mode == 7:
        return _lerp(a, (a[0] + b[0], a[1] + b[1], a[2] + b[2]), t)
    if mode == 8:
        return (_overlay(a[0], b[0], t), _overlay(a[1], b[1], t), _overlay(a[2], b[2], t))
    if mode == 9:
        return (_soft_light(a[0], b[0], t), _soft_light(a[1], b[1], t), _soft_light(a[2], b[2], t))
    if mode == 10:
        return (a[0] + t * (2.0 * b[0] - 1.0), a[1] + t * (2.0 * b[1] - 1.0), a[2] + t * (2.0 * b[2] - 1.0))
    if mode == 11:
        return _lerp(a, (abs(a[0] - b[0]), abs(a[1] - b[1]), abs(a[2] - b[2])), t)
    if mode == 12:
        e = _lerp(a, (a[0] + b[0] - 2.0 * a[0] * b[0], a[1] + b[1] - 2.0 * a[1] * b[1],
                      a[2] + b[2] - 2.0 * a[2] * b[2]), t)
        return (max(e[0], 0.0), max(e[1], 0.0), max(e[2], 0.0))
    if mode == 13:
        return _lerp(a, (a[0] - b[0], a[1] - b[1], a[2] - b[2]), t)
    if mode == 14:
        return (_divide(a[0], b[0], t), _divide(a[1], b[1], t), _divide(a[2], b[2], t))
    if mode == 15:
        hsv_b = rgb_to_hsv(b)
        if hsv_b[1] == 0.0:
            return a
        hsv_a = rgb_to_hsv(a)
        return _lerp(a, hsv_to_rgb((hsv_b[0], hsv_a[1], hsv_a[2])), t)
    if mode == 16:
        hsv_a = rgb_to_hsv(a)
        if hsv_a[1] == 0.0:
            return a
        hsv_b = rgb_to_hsv(b)
        return hsv_to_rgb((hsv_a[0], (1.0 - t) * hsv_a[1] + t * hsv_b[1], hsv_a[2]))
    if mode == 17:
        hsv_b = rgb_to_hsv(b)
        if hsv_b[1] == 0.0:
            return a
        hsv_a = rgb_to_hsv(a)
        return _lerp(a, hsv_to_rgb((hsv_b[0], hsv_b[1], hsv_a[2])), t)
    if mode == 18:
        hsv_a = rgb_to_hsv(a)
        hsv_b = rgb_to_hsv(b)
        return hsv_to_rgb((hsv_a[0], hsv_a[1], (1.0 - t) * hsv_a[2] + t * hsv_b[2]))
    return (0.0, 0.0, 0.0)


@kernel
def hue_saturation_value(hue, saturation, value, fac, c):
    """Blender's Hue/Saturation/Value node (hue 0.5 = unchanged)."""
    h, s, v = rgb_to_hsv(c)
    h = h + hue + 0.5
    h = h - math.floor(h)
    s = min(max(s * saturation, 0.0), 1.0)
    out = hsv_to_rgb((h, s, v * value))
    return (max(fac * out[0] + (1.0 - fac) * c[0], 0.0), max(fac * out[1] + (1.0 - fac) * c[1], 0.0),
            max(fac * out[2] + (1.0 - fac) * c[2], 0.0))


@kernel
def bright_contrast(c, bright, contrast):
    a = 1.0 + contrast
    b = bright - contrast * 0.5
    return (max(a * c[0] + b, 0.0), max(a * c[1] + b, 0.0), max(a * c[2] + b, 0.0))


@kernel
def invert(fac, c):
    return (fac * (1.0 - c[0]) + (1.0 - fac) * c[0], fac * (1.0 - c[1]) + (1.0 - fac) * c[1],
            fac * (1.0 - c[2]) + (1.0 - fac) * c[2])


@kernel
def gamma(c, g):
    if g == 0.0:
        return (1.0, 1.0, 1.0)
    return (c[0] ** g if c[0] > 0.0 else c[0], c[1] ** g if c[1] > 0.0 else c[1], c[2] ** g if c[2] > 0.0 else c[2])


@kernel
def table_lookup(table, first, size, stride, channel, f, interpolate, extrapolate):
    """Entry ``channel`` of a table of ``size`` rows of ``stride`` values starting at ``table[first]``, at
    ``f`` in [0, 1] (linear between rows if ``interpolate``; beyond the ends, linear continuation of the
    last segment if ``extrapolate``, else the end rows)."""
    if extrapolate and (f < 0.0 or f > 1.0):
        if f < 0.0:
            t0 = table[first + channel]
            dy = t0 - table[first + stride + channel]
            f = -f
        else:
            t0 = table[first + (size - 1) * stride + channel]
            dy = t0 - table[first + (size - 2) * stride + channel]
            f = f - 1.0
        return t0 + dy * f * (size - 1)
    if not f > 0.0:
        f = 0.0
    x = min(f, 1.0) * (size - 1)
    i = min(int(x), size - 1)
    t = x - i
    value = table[first + i * stride + channel]
    if interpolate and t > 0.0:
        value = (1.0 - t) * value + t * table[first + (i + 1) * stride + channel]
    return value
