"""Warps of uniform numbers in [0, 1)² to points and directions, per path (pdfs in the docstrings)."""

from __future__ import annotations

import math

from .jit import kernel


# Taylor coefficients of sin and cos up to x^11 and x^12: on |x| <= π/4 both are within 7e-12 of
# the libm values, at a third of the cost of a libm sin + cos (warps run several times per bounce).
_S3, _S5, _S7, _S9, _S11 = -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0, -1.0 / 39916800.0
_C2, _C4, _C6, _C8, _C10, _C12 = -0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0, -1.0 / 3628800.0, 1.0 / 479001600.0
_HALF_SQRT2 = math.sqrt(0.5)


@kernel
def sincos_quarter(x):
    """(sin x, cos x) for |x| <= π/4."""
    x2 = x * x
    s = x * (1.0 + x2 * (_S3 + x2 * (_S5 + x2 * (_S7 + x2 * (_S9 + x2 * _S11)))))
    c = 1.0 + x2 * (_C2 + x2 * (_C4 + x2 * (_C6 + x2 * (_C8 + x2 * (_C10 + x2 * _C12)))))
    return s, c


@kernel
def sincos_turn(u):
    """(sin 2πu, cos 2πu) for u in [0, 1): the quadrant, then ±π/4 about its middle."""
    q4 = 4.0 * u
    q = min(int(q4), 3)
    s, c = sincos_quarter((q4 - q - 0.5) * (math.pi / 2.0))
    # angle = q π/2 + π/4 + ψ: rotate (cos, sin) of ψ by π/4, then by q quarter turns
    cos_a = _HALF_SQRT2 * (c - s)
    sin_a = _HALF_SQRT2 * (c + s)
    if q == 0:
        return sin_a, cos_a
    if q == 1:
        return cos_a, -sin_a
    if q == 2:
        return -sin_a, -cos_a
    return -cos_a, sin_a


@kernel
def concentric_disk(u1, u2):
    """Shirley-Chiu map to the unit disk (area-uniform, pdf 1/π)."""
    a = 2.0 * u1 - 1.0
    b = 2.0 * u2 - 1.0
    if a == 0.0 and b == 0.0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        s, c = sincos_quarter((math.pi / 4.0) * (b / a))
        return a * c, a * s
    s, c = sincos_quarter((math.pi / 4.0) * (a / b))  # the angle is π/2 - this: swap sin and cos
    return b * s, b * c


@kernel
def regular_polygon(u1, u2, corners, rotation):
    """Area-uniform point of the regular polygon inscribed in the unit circle with ``corners`` corners at
    angles rotation + (2k + 1)π/corners (an edge's midpoint on +X when rotation is 0); density 1/area."""
    corner = min(int(u1 * corners), corners - 1)
    u = u1 * corners - corner
    s = math.sqrt(u)
    a = 1.0 - s  # barycentrics of the corner triangle (centre, corner k, corner k + 1)
    b = u2 * s
    half = math.pi / corners
    x, y = (a + b) * math.cos(half), (a - b) * math.sin(half)
    angle = rotation + 2.0 * half * corner
    c, sn = math.cos(angle), math.sin(angle)
    return c * x - sn * y, sn * x + c * y


@kernel
def cosine_hemisphere(u1, u2):
    """Cosine-weighted direction about +Z; pdf cos(θ)/π."""
    x, y = concentric_disk(u1, u2)
    return (x, y, math.sqrt(max(0.0, 1.0 - x * x - y * y)))


@kernel
def uniform_cone(u1, u2, cos_max):
    """Uniform direction in the cone about +Z of half-angle acos(cos_max); pdf 1 / (2π (1 - cos_max))."""
    z = 1.0 - u1 * (1.0 - cos_max)
    r = math.sqrt(max(0.0, 1.0 - z * z))
    s, c = sincos_turn(u2)
    return (r * c, r * s, z)


@kernel
def uniform_sphere(u1, u2):
    """Uniform direction on the unit sphere; pdf 1/(4π)."""
    z = 1.0 - 2.0 * u1
    r = math.sqrt(max(0.0, 1.0 - z * z))
    s, c = sincos_turn(u2)
    return (r * c, r * s, z)


@kernel
def uniform_triangle(u1, u2):
    """Area-uniform barycentrics (b1, b2) of a triangle (square-root warp); corner weights (1-b1-b2, b1, b2)."""
    s = math.sqrt(u1)
    return 1.0 - s, u2 * s


@kernel
def power_heuristic(pdf_a, pdf_b):
    """Veach's power heuristic (β = 2) weight of strategy a against b; 1 when a is a delta (inf)."""
    if math.isinf(pdf_a):
        return 1.0
    a2 = pdf_a * pdf_a
    b2 = pdf_b * pdf_b
    if not (a2 + b2 > 0.0) or math.isinf(b2):
        return 0.0
    return a2 / (a2 + b2)


@kernel
def cdf_index(cdf, u):
    """The bin a uniform ``u`` falls in: the first index whose value in the increasing ``cdf`` (its last
    value 1) exceeds ``u``, by binary search."""
    lo, hi = 0, cdf.shape[0] - 1
    while lo < hi:
        mid = (lo + hi) >> 1
        if cdf[mid] <= u:
            lo = mid + 1
        else:
            hi = mid
    return lo
