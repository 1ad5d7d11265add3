"""Cycles' shadow terminator Geometry Offset (Object ▸ Shading ▸ Shadow Terminator ▸ Geometry Offset, 0.1 by
default): shadow rays from smooth-shaded triangles start on a curved surface through the corners instead of on
the flat triangle.

A coarse mesh shaded smooth lights points whose flat triangle faces away from the light, or lies in the shadow
of the next triangle, although its interpolated normal still faces it: a band of hard, faceted shadow along the
terminator. Cycles lifts the shadow ray's origin by the height of a surface that the corner normals describe
(Hanika 2021, "Hacking the Shadow Terminator", Ray Tracing Gems II ch. 4: a quadratic patch, bounded by the
planes through each corner normal to its normal), and only for rays toward lights close to the terminator: the
lift fades in as the light's cosine to the shading or geometric normal falls below the offset.
The formulas are those of Cycles 4.5 ``kernel/light/sample.h`` (``shadow_ray_offset``,
``shadow_ray_smooth_surface_offset``); Cycles applies them to light sampling's shadow rays and the AO pass's rays.

The Shading Offset (0 by default) softens the light each closure receives toward its normal's horizon
(``bsdf.closure_frame.terminator_softening``); ``soften_closures`` hands a hit's closures the multiplier.

``Geometry.terminator`` float32 [T, 2] holds each triangle's Geometry Offset (0 for flat-shaded faces and meshes
without corner normals) and Shading Offset multiplier (0: none), or is empty when no triangle has either.
"""

from __future__ import annotations

import math

from .bsdf.closure import C_TERMINATOR
from .geometry import corner_normal, vertex_at
from .jit import inlined, kernel
from .vec3 import dot, sub

ZERO_LIFT = (0.0, 0.0, 0.0)


@kernel
def _envelope(apex, others_a, others_b, n, p, outward):
    """How far the plane through corner ``apex`` normal to its normal ``n`` lies above ``p`` (``outward``: the
    normals face the side the ray leaves from), lifted so that it bounds the triangle's other two corners."""
    if outward:
        reach = max(max(dot(sub(others_a, apex), n), dot(sub(others_b, apex), n)), 0.0)
        return max(dot(sub(apex, p), n) + reach, 0.0)
    reach = max(max(dot(sub(apex, others_a), n), dot(sub(apex, others_b), n)), 0.0)
    return max(dot(sub(p, apex), n) + reach, 0.0)


@inlined
def smooth_surface_offset(geometry, triangle, u, v, ng, time):
    """The vector from barycentrics (u, v) of ``triangle`` to the smooth surface its corner normals describe, on
    the side of ``ng`` (the geometric normal of the side the ray leaves from): the interpolated normal (not unit)
    times the patch's height there."""
    v0 = vertex_at(geometry, geometry.triangles[triangle, 0], time)
    v1 = vertex_at(geometry, geometry.triangles[triangle, 1], time)
    v2 = vertex_at(geometry, geometry.triangles[triangle, 2], time)
    n0 = corner_normal(geometry, triangle, 0, time)
    n1 = corner_normal(geometry, triangle, 1, time)
    n2 = corner_normal(geometry, triangle, 2, time)
    w0, w1, w2 = 1.0 - u - v, u, v
    p = (w0 * v0[0] + w1 * v1[0] + w2 * v2[0], w0 * v0[1] + w1 * v1[1] + w2 * v2[1],
         w0 * v0[2] + w1 * v1[2] + w2 * v2[2])
    n = (w0 * n0[0] + w1 * n1[0] + w2 * n2[0], w0 * n0[1] + w1 * n1[1] + w2 * n2[1],
         w0 * n0[2] + w1 * n1[2] + w2 * n2[2])
    # the quadratic patch through the corners with the corner normals (a parabolic approximation)
    a = dot(sub(n2, n0), sub(v0, v2))
    b = dot(sub(n2, n1), sub(v1, v2))
    c = dot(sub(n1, n0), sub(v1, v0))
    h = a * w0 * (w0 - 1.0) + (a + b + c) * w0 * w1 + b * w1 * (w1 - 1.0)
    outward = dot(n, ng) > 0.0
    h0 = _envelope(v0, v1, v2, n0, p, outward)
    h1 = _envelope(v1, v0, v2, n1, p, outward)
    h2 = _envelope(v2, v0, v1, n2, p, outward)
    if outward:
        h = max(min(min(h0, h1), h2), 0.5 * h)
    else:
        h = min(-min(min(h0, h1), h2), 0.5 * h)
    return (n[0] * h, n[1] * h, n[2] * h)


@inlined
def terminator_lift(geometry, triangle, u, v, ng, ns, toward, time):
    """What Cycles adds to the origin of a shadow ray leaving barycentrics (u, v) of ``triangle`` toward unit
    ``toward``; ``ng``: the geometric normal (either side), ``ns``: the smooth shading normal on the side the path
    arrived from. ``ZERO_LIFT`` for flat faces, other primitives, objects whose offset is 0, and lights well above
    the terminator."""
    if geometry.terminator.shape[0] == 0 or triangle >= geometry.triangles.shape[0]:
        return ZERO_LIFT
    cutoff = float(geometry.terminator[triangle, 0])
    if not cutoff > 0.0:
        return ZERO_LIFT
    nl = dot(ns, toward)
    if (nl < 0.0) != (dot(ng, ns) < 0.0):  # ng onto the side the ray leaves from: the view's, or behind for
        ng = (-ng[0], -ng[1], -ng[2])      # a light behind
    nl = abs(nl)
    ngl = dot(ng, toward)
    if nl < cutoff:
        amount = min(max(2.0 - (ngl + nl) / cutoff, 0.0), 1.0)
    else:
        amount = min(max(1.0 - ngl / cutoff, 0.0), 1.0)
    if not amount > 0.0:
        return ZERO_LIFT
    lift = smooth_surface_offset(geometry, triangle, u, v, ng, time)
    return (lift[0] * amount, lift[1] * amount, lift[2] * amount)


@inlined
def lifted_ray(p, lift, toward, distance):
    """(origin, unit direction, distance) of a shadow ray from ``p`` toward a light sample ``distance`` away
    along ``toward`` (infinite: a distant light), started at ``p`` + ``lift``: aimed again at the sample, as Cycles
    aims it (``shadow_ray_setup``), so that it neither stops short of the light nor passes it."""
    if lift[0] == 0.0 and lift[1] == 0.0 and lift[2] == 0.0:
        return p, toward, distance
    start = (p[0] + lift[0], p[1] + lift[1], p[2] + lift[2])
    if not math.isfinite(distance):
        return start, toward, distance
    d = (p[0] + toward[0] * distance - start[0], p[1] + toward[1] * distance - start[1],
         p[2] + toward[2] * distance - start[2])
    length = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    if not length > 0.0:
        return start, toward, distance
    return start, (d[0] / length, d[1] / length, d[2] / length), length


@inlined
def soften_closures(geometry, triangle, rows, count):
    """Give the ``count`` closures in ``rows`` of a hit on ``triangle`` its object's Shading Offset multiplier (the
    rows come from the material, which holds none)."""
    if geometry.terminator.shape[0] == 0 or triangle >= geometry.triangles.shape[0]:
        return
    multiplier = geometry.terminator[triangle, 1]
    if multiplier > 1.0:
        for c in range(count):
            rows[c, C_TERMINATOR] = multiplier
