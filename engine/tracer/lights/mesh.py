"""Emissive triangles (materials with emission) as one light.

Emission is two-sided with radiance strength × spectrum (Cycles' Emission). For light sampling a
triangle is picked with probability ∝ area × strength and a point uniformly on it; densities are
converted to solid angle so BSDF-sampled hits on the same triangles are weighted by MIS. With motion blur the
point is drawn on the triangle where it stands at the path's ray time (its area then), and the density of a
hit is taken there too.

``MeshEmitters``: ``triangle`` int32 [E] (geometry triangle ids), ``material`` int32 [E], ``geometry`` float64 [E, 13] (v0, e1,
e2, unit normal, area; camera-relative metres), ``cdf`` / ``probability`` float64 [E], ``of_triangle``
int32 [T] (emitter row of each geometry triangle, -1 if it does not emit), ``group`` int32 [E] (light
group, -1: none), ``total`` (Σ area × strength, for light selection).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..geometry import vertex_at
from ..jit import inlined
from ..warps import cdf_index, uniform_triangle

MeshEmitters = namedtuple("MeshEmitters", "triangle material geometry cdf probability of_triangle group")


def build_mesh_emitters(vertices, triangles, triangle_material, strength_of_material, triangle_group=None):
    """Emitters of the triangles whose material has strength > 0 (``strength_of_material`` [M]);
    ``triangle_group`` [T] their light groups (None: none). Returns (``MeshEmitters``, total area × strength) — (empty tables, 0) when nothing emits."""
    strength = strength_of_material[triangle_material] if len(triangle_material) else np.zeros(0)
    emitting = np.flatnonzero(strength > 0)
    corners = np.asarray(vertices, np.float64)[np.asarray(triangles)[emitting]]
    e1 = corners[:, 1] - corners[:, 0]
    e2 = corners[:, 2] - corners[:, 0]
    cross = np.cross(e1, e2)
    double_area = np.linalg.norm(cross, axis=1)
    keep = np.isfinite(double_area) & (double_area > 0)
    emitting, corners, e1, e2, cross, double_area = (a[keep] for a in (emitting, corners, e1, e2, cross, double_area))
    of_triangle = np.full(len(triangles), -1, np.int32)
    if len(emitting) == 0:
        empty = MeshEmitters(np.zeros(0, np.int32), np.zeros(0, np.int32), np.zeros((0, 13)), np.zeros(0),
                             np.zeros(0), of_triangle, np.zeros(0, np.int32))
        return empty, 0.0
    area = 0.5 * double_area
    geometry = np.concatenate([corners[:, 0], e1, e2, cross / double_area[:, None], area[:, None]], axis=1)
    weight = area * strength[emitting]
    total = float(weight.sum())
    probability = weight / total
    cdf = np.cumsum(probability)
    cdf[-1] = 1.0
    of_triangle[emitting] = np.arange(len(emitting), dtype=np.int32)
    material = np.asarray(triangle_material)[emitting].astype(np.int32)
    group = (np.asarray(triangle_group, np.int32)[emitting] if triangle_group is not None
             else np.full(len(emitting), -1, np.int32))
    return MeshEmitters(emitting.astype(np.int32), material, geometry, cdf, probability, of_triangle, group), total


@inlined
def pick(emitters, u):
    """The emitter row whose cdf interval holds ``u``."""
    return cdf_index(emitters.cdf, u)


@inlined
def emitter_at(emitters, geometry, e, time):
    """(first corner, edge 1, edge 2, unit normal, area) of emitter row ``e`` where its triangle stands at ray time
    ``time``: the table's (the frame's) when nothing moves, else from ``geometry``'s vertices then, so light
    sampling finds a moving emitter where the ray that checks its visibility does."""
    g = emitters.geometry[e]
    if geometry.motion.shape[0] == 0 or time < 0.0:
        return (g[0], g[1], g[2]), (g[3], g[4], g[5]), (g[6], g[7], g[8]), (g[9], g[10], g[11]), g[12]
    t = emitters.triangle[e]
    a = vertex_at(geometry, geometry.triangles[t, 0], time)
    b = vertex_at(geometry, geometry.triangles[t, 1], time)
    c = vertex_at(geometry, geometry.triangles[t, 2], time)
    e1 = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
    e2 = (c[0] - a[0], c[1] - a[1], c[2] - a[2])
    n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
    double_area = math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    if not double_area > 0.0:  # degenerate at this time: nothing to sample
        return a, e1, e2, (g[9], g[10], g[11]), 0.0
    return a, e1, e2, (n[0] / double_area, n[1] / double_area, n[2] / double_area), 0.5 * double_area


@inlined
def sample_point(emitters, geometry, p, u0, u1, u2, time):
    """(wi, distance, solid-angle pdf, emitter row, barycentrics b1, b2) of a point on an emissive triangle, seen
    from ``p`` at ray time ``time``."""
    e = pick(emitters, u0)
    v0, e1, e2, n, area = emitter_at(emitters, geometry, e, time)
    b1, b2 = uniform_triangle(u1, u2)
    wx = v0[0] + b1 * e1[0] + b2 * e2[0] - p[0]
    wy = v0[1] + b1 * e1[1] + b2 * e2[1] - p[1]
    wz = v0[2] + b1 * e1[2] + b2 * e2[2] - p[2]
    dist = math.sqrt(wx * wx + wy * wy + wz * wz)
    if dist <= 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0, e, b1, b2
    wi = (wx / dist, wy / dist, wz / dist)
    cos_l = abs(wi[0] * n[0] + wi[1] * n[1] + wi[2] * n[2])
    if cos_l <= 0.0 or not area > 0.0:
        return wi, dist, 0.0, e, b1, b2
    return wi, dist, emitters.probability[e] / area * dist * dist / cos_l, e, b1, b2


@inlined
def pdf_li(emitters, geometry, triangle, d, t, time):
    """Solid-angle density of ``sample_point`` for a ray along ``d`` hitting ``triangle`` at distance ``t`` at ray
    time ``time``."""
    e = emitters.of_triangle[triangle]
    if e < 0:
        return 0.0
    _, _, _, n, area = emitter_at(emitters, geometry, e, time)
    cos_l = abs(d[0] * n[0] + d[1] * n[1] + d[2] * n[2])
    if cos_l <= 0.0 or not area > 0.0:
        return 0.0
    return emitters.probability[e] / area * t * t / cos_l


@inlined
def sample_position(emitters, geometry, u0, u1, u2, time):
    """(point, unit geometric normal, area density incl. the triangle's choice, material, emitter index,
    barycentrics b1, b2) of a point on an emissive triangle at ray time ``time``: where a light path starts."""
    e = pick(emitters, u0)
    v0, e1, e2, n, area = emitter_at(emitters, geometry, e, time)
    b1, b2 = uniform_triangle(u1, u2)
    p = (v0[0] + b1 * e1[0] + b2 * e2[0], v0[1] + b1 * e1[1] + b2 * e2[1], v0[2] + b1 * e1[2] + b2 * e2[2])
    density = emitters.probability[e] / area if area > 0.0 else 0.0
    return p, n, density, emitters.material[e], e, b1, b2
