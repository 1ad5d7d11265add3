"""3-vectors as tuples of three floats, for per-path kernel code (numba keeps them in registers).

Directions are unit vectors unless a name says otherwise; positions are metres relative to the camera
(see ``accel``). Local shading frames are (s, t, n) with n the normal (+Z of the local frame).
"""

from __future__ import annotations

import math

from .jit import kernel


@kernel
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@kernel
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@kernel
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@kernel
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


@kernel
def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


@kernel
def along(p, t, d):
    """p + t d."""
    return (p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2])


@kernel
def neg(a):
    return (-a[0], -a[1], -a[2])


@kernel
def length(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


@kernel
def normalize(a):
    """Unit vector along ``a`` (the zero vector stays zero)."""
    n = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    if n > 0.0:
        return (a[0] / n, a[1] / n, a[2] / n)
    return (0.0, 0.0, 0.0)


@kernel
def tangents(n):
    """Tangents (s, t) completing unit ``n`` to a right-handed orthonormal frame (Duff et al. 2017)."""
    sign = 1.0 if n[2] >= 0.0 else -1.0
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    s = (1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0])
    t = (b, sign + n[1] * n[1] * a, -n[1])
    return s, t


@kernel
def to_local(v, s, t, n):
    return (dot(v, s), dot(v, t), dot(v, n))


@kernel
def to_world(v, s, t, n):
    return (
        v[0] * s[0] + v[1] * t[0] + v[2] * n[0],
        v[0] * s[1] + v[1] * t[1] + v[2] * n[1],
        v[0] * s[2] + v[1] * t[2] + v[2] * n[2],
    )


@kernel
def transform(m, v):
    """3x3 matrix ``m`` (a [3,3] array) times vector ``v``."""
    return (
        m[0, 0] * v[0] + m[0, 1] * v[1] + m[0, 2] * v[2],
        m[1, 0] * v[0] + m[1, 1] * v[1] + m[1, 2] * v[2],
        m[2, 0] * v[0] + m[2, 1] * v[1] + m[2, 2] * v[2],
    )
