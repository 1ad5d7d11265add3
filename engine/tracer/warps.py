"""Warps of uniform numbers in [0, 1)² to points and directions, per path (pdfs in the docstrings)."""

from __future__ import annotations

import math

from .jit import kernel


@kernel
def concentric_disk(u1, u2):
    """Shirley-Chiu map to the unit disk (area-uniform, pdf 1/π)."""
    a = 2.0 * u1 - 1.0
    b = 2.0 * u2 - 1.0
    if a == 0.0 and b == 0.0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        r = a
        phi = (math.pi / 4.0) * (b / a)
    else:
        r = b
        phi = math.pi / 2.0 - (math.pi / 4.0) * (a / b)
    return r * math.cos(phi), r * math.sin(phi)


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
    phi = 2.0 * math.pi * u2
    return (r * math.cos(phi), r * math.sin(phi), z)


@kernel
def uniform_sphere(u1, u2):
    """Uniform direction on the unit sphere; pdf 1/(4π)."""
    z = 1.0 - 2.0 * u1
    r = math.sqrt(max(0.0, 1.0 - z * z))
    phi = 2.0 * math.pi * u2
    return (r * math.cos(phi), r * math.sin(phi), z)


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
