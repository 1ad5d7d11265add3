"""Blender's Math, Vector Math, Map Range and Clamp nodes, as scalar kernel code.

Semantics follow Blender's documentation of each operation, including its guards: divisions by zero
give 0, ``Power`` of a negative base with a fractional exponent gives 0, ``Logarithm`` of a non-positive
number gives 0, arcsine/arccosine clamp their argument, ``Compare`` uses the epsilon as a tolerance.
Modes are indices into ``materials.opcodes.MATH_OPERATIONS`` / ``VECTOR_MATH_OPERATIONS``.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel

_FLOAT32_EPSILON = 1.1920928955078125e-07


@kernel
def safe_divide(a, b):
    return a / b if b != 0.0 else 0.0


@kernel
def safe_power(a, b):
    if a < 0.0 and b != float(int(b)):
        return 0.0
    if a == 0.0 and b < 0.0:
        return math.inf
    return a**b


@kernel
def safe_modulo(a, b):
    return np.fmod(a, b) if b != 0.0 else 0.0


@kernel
def wrap(value, upper, lower):
    span = upper - lower
    return value - span * math.floor((value - lower) / span) if span != 0.0 else lower


@kernel
def ping_pong(a, b):
    if b == 0.0:
        return 0.0
    x = (a - b) / (b * 2.0)
    return abs((x - math.floor(x)) * b * 2.0 - b)


@kernel
def smooth_min(a, b, k):
    if k != 0.0:
        h = max(k - abs(a - b), 0.0) / k
        return min(a, b) - h * h * h * k / 6.0
    return min(a, b)


@kernel
def sign(a):
    if a > 0.0:
        return 1.0
    if a < 0.0:
        return -1.0
    return 0.0


@kernel
def math_operation(mode, a, b, c):
    """Blender's Math node (``MATH_OPERATIONS[mode]``)."""
    if mode == 0:
        return a + b
    if mode == 1:
        return a - b
    if mode == 2:
        return a * b
    if mode == 3:
        return safe_divide(a, b)
    if mode == 4:
        return a * b + c
    if mode == 5:
        return safe_power(a, b)
    if mode == 6:
        return safe_divide(math.log(a), math.log(b)) if a > 0.0 and b > 0.0 else 0.0
    if mode == 7:
        return math.sqrt(max(a, 0.0))
    if mode == 8:
        return 1.0 / math.sqrt(a) if a > 0.0 else 0.0
    if mode == 9:
        return abs(a)
    if mode == 10:
        return math.exp(a) if a < 700.0 else math.inf
    if mode == 11:
        return min(a, b)
    if mode == 12:
        return max(a, b)
    if mode == 13:
        return 1.0 if a < b else 0.0
    if mode == 14:
        return 1.0 if a > b else 0.0
    if mode == 15:
        return sign(a)
    if mode == 16:
        return 1.0 if a == b or abs(a - b) <= max(c, _FLOAT32_EPSILON) else 0.0
    if mode == 17:
        return smooth_min(a, b, c)
    if mode == 18:
        return -smooth_min(-a, -b, c)
    if mode == 19:
        return math.floor(a + 0.5)
    if mode == 20:
        return math.floor(a)
    if mode == 21:
        return math.ceil(a)
    if mode == 22:
        return math.floor(a) if a >= 0.0 else math.ceil(a)
    if mode == 23:
        return a - math.floor(a)
    if mode == 24:
        return safe_modulo(a, b)
    if mode == 25:
        return a - math.floor(a / b) * b if b != 0.0 else 0.0
    if mode == 26:
        return wrap(a, b, c)
    if mode == 27:
        return math.floor(safe_divide(a, b)) * b
    if mode == 28:
        return ping_pong(a, b)
    if mode == 29:
        return math.sin(a)
    if mode == 30:
        return math.cos(a)
    if mode == 31:
        return math.tan(a)
    if mode == 32:
        return math.asin(min(max(a, -1.0), 1.0))
    if mode == 33:
        return math.acos(min(max(a, -1.0), 1.0))
    if mode == 34:
        return math.atan(a)
    if mode == 35:
        return 0.0 if a == 0.0 and b == 0.0 else math.atan2(a, b)
    if mode == 36:
        return math.sinh(a) if abs(a) < 700.0 else math.copysign(math.inf, a)
    if mode == 37:
        return math.cosh(a) if abs(a) < 700.0 else math.inf
    if mode == 38:
        return math.tanh(a)
    if mode == 39:
        return a * (math.pi / 180.0)
    if mode == 40:
        return a * (180.0 / math.pi)
    return 0.0


@kernel
def _normalized(x, y, z):
    n = math.sqrt(x * x + y * y + z * z)
    if n != 0.0:
        return x / n, y / n, z / n
    return x, y, z


@kernel
def vector_math(mode, a, b, c, s):
    """Blender's Vector Math node (``VECTOR_MATH_OPERATIONS[mode]``) on 3-tuples ``a``, ``b``, ``c`` and the
    scalar ``s`` (Scale, IOR): (vector result, scalar result)."""
    zero = (0.0, 0.0, 0.0)
    if mode == 0:
        return (a[0] + b[0], a[1] + b[1], a[2] + b[2]), 0.0
    if mode == 1:
        return (a[0] - b[0], a[1] - b[1], a[2] - b[2]), 0.0
    if mode == 2:
        return (a[0] * b[0], a[1] * b[1], a[2] * b[2]), 0.0
    if mode == 3:
        return (safe_divide(a[0], b[0]), safe_divide(a[1], b[1]), safe_divide(a[2], b[2])), 0.0
    if mode == 4:
        return (a[0] * b[0] + c[0], a[1] * b[1] + c[1], a[2] * b[2] + c[2]), 0.0
    if mode == 5:
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]), 0.0
    if mode == 6:
        length2 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
        if length2 == 0.0:
            return zero, 0.0
        t = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / length2
        return (t * b[0], t * b[1], t * b[2]), 0.0
    if mode == 7:
        nx, ny, nz = _normalized(b[0], b[1], b[2])
        d = 2.0 * (a[0] * nx + a[1] * ny + a[2] * nz)
        return (a[0] - d * nx, a[1] - d * ny, a[2] - d * nz), 0.0
    if mode == 8:
        nx, ny, nz = _normalized(b[0], b[1], b[2])
        cos = nx * a[0] + ny * a[1] + nz * a[2]
        k = 1.0 - s * s * (1.0 - cos * cos)
        if k < 0.0:
            return zero, 0.0
        q = s * cos + math.sqrt(k)
        return (s * a[0] - q * nx, s * a[1] - q * ny, s * a[2] - q * nz), 0.0
    if mode == 9:
        if b[0] * c[0] + b[1] * c[1] + b[2] * c[2] < 0.0:
            return (a[0], a[1], a[2]), 0.0
        return (-a[0], -a[1], -a[2]), 0.0
    if mode == 10:
        return zero, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    if mode == 11:
        dx, dy, dz = a[0] - b[0], a[1] - b[1], a[2] - b[2]
        return zero, math.sqrt(dx * dx + dy * dy + dz * dz)
    if mode == 12:
        return zero, math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    if mode == 13:
        return (a[0] * s, a[1] * s, a[2] * s), 0.0
    if mode == 14:
        return _normalized(a[0], a[1], a[2]), 0.0
    if mode == 15:
        return (abs(a[0]), abs(a[1]), abs(a[2])), 0.0
    if mode == 16:
        return (safe_power(a[0], b[0]), safe_power(a[1], b[1]), safe_power(a[2], b[2])), 0.0
    if mode == 17:
        return (sign(a[0]), sign(a[1]), sign(a[2])), 0.0
    if mode == 18:
        return (min(a[0], b[0]), min(a[1], b[1]), min(a[2], b[2])), 0.0
    if mode == 19:
        return (max(a[0], b[0]), max(a[1], b[1]), max(a[2], b[2])), 0.0
    if mode == 20:
        return (math.floor(a[0]), math.floor(a[1]), math.floor(a[2])), 0.0
    if mode == 21:
        return (math.ceil(a[0]), math.ceil(a[1]), math.ceil(a[2])), 0.0
    if mode == 22:
        return (a[0] - math.floor(a[0]), a[1] - math.floor(a[1]), a[2] - math.floor(a[2])), 0.0
    if mode == 23:
        return (safe_modulo(a[0], b[0]), safe_modulo(a[1], b[1]), safe_modulo(a[2], b[2])), 0.0
    if mode == 24:
        return (wrap(a[0], b[0], c[0]), wrap(a[1], b[1], c[1]), wrap(a[2], b[2], c[2])), 0.0
    if mode == 25:
        return (math.floor(safe_divide(a[0], b[0])) * b[0], math.floor(safe_divide(a[1], b[1])) * b[1],
                math.floor(safe_divide(a[2], b[2])) * b[2]), 0.0
    if mode == 26:
        return (math.sin(a[0]), math.sin(a[1]), math.sin(a[2])), 0.0
    if mode == 27:
        return (math.cos(a[0]), math.cos(a[1]), math.cos(a[2])), 0.0
    if mode == 28:
        return (math.tan(a[0]), math.tan(a[1]), math.tan(a[2])), 0.0
    return zero, 0.0


@kernel
def _smoothstep(edge0, edge1, x):
    t = min(max(safe_divide(x - edge0, edge1 - edge0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


@kernel
def _smootherstep(edge0, edge1, x):
    t = min(max(safe_divide(x - edge0, edge1 - edge0), 0.0), 1.0)
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


@kernel
def map_range(mode, value, from_min, from_max, to_min, to_max, steps, clamp):
    """Blender's Map Range node (float), ``MAP_RANGE_MODES[mode]``; ``clamp`` applies to linear and
    stepped mapping as in Blender."""
    if from_max == from_min:
        return 0.0
    if mode == 0 or mode == 1:
        factor = (value - from_min) / (from_max - from_min)
        if mode == 1:
            factor = math.floor(factor * (steps + 1.0)) / steps if steps > 0.0 else 0.0
    elif mode == 2:
        factor = 1.0 - _smoothstep(from_max, from_min, value) if from_min > from_max else _smoothstep(
            from_min, from_max, value)
    else:
        factor = 1.0 - _smootherstep(from_max, from_min, value) if from_min > from_max else _smootherstep(
            from_min, from_max, value)
    result = to_min + factor * (to_max - to_min)
    if clamp and mode <= 1:
        lo, hi = (to_max, to_min) if to_min > to_max else (to_min, to_max)
        result = min(max(result, lo), hi)
    return result


@kernel
def clamp_value(mode, value, lo, hi):
    """Blender's Clamp node: mode 0 min-max, 1 range (the bounds may come in either order)."""
    if mode == 1 and lo > hi:
        lo, hi = hi, lo
    return min(max(value, lo), hi)
