"""Emissive triangles (materials with emission) as one light.

Emission is two-sided with radiance strength × spectrum (Cycles' Emission). For light sampling a
triangle is picked with probability ∝ area × strength and a point uniformly on it; densities are
converted to solid angle so BSDF-sampled hits on the same triangles are weighted by MIS.

``MeshEmitters``: ``triangle`` int32 [E] (geometry triangle ids), ``material`` int32 [E], ``geometry`` float64 [E, 13] (v0, e1,
e2, unit normal, area; camera-relative metres), ``cdf`` / ``probability`` float64 [E], ``of_triangle``
int32 [T] (emitter row of each geometry triangle, -1 if it does not emit), ``group`` int32 [E] (light
group, -1: none), ``total`` (Σ area × strength, for light selection).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

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
def sample_li(emitters, p, u0, u1, u2):
    """(wi, distance, solid-angle pdf, emitter row) of a point on an emissive triangle."""
    wi, dist, pdf, e, _, _ = sample_point(emitters, p, u0, u1, u2)
    return wi, dist, pdf, e


@inlined
def sample_point(emitters, p, u0, u1, u2):
    """``sample_li`` and where the point is on its triangle: (..., barycentrics b1, b2)."""
    e = pick(emitters, u0)
    g = emitters.geometry[e]
    b1, b2 = uniform_triangle(u1, u2)
    wx = g[0] + b1 * g[3] + b2 * g[6] - p[0]
    wy = g[1] + b1 * g[4] + b2 * g[7] - p[1]
    wz = g[2] + b1 * g[5] + b2 * g[8] - p[2]
    dist = math.sqrt(wx * wx + wy * wy + wz * wz)
    if dist <= 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0, e, b1, b2
    wi = (wx / dist, wy / dist, wz / dist)
    cos_l = abs(wi[0] * g[9] + wi[1] * g[10] + wi[2] * g[11])
    if cos_l <= 0.0:
        return wi, dist, 0.0, e, b1, b2
    return wi, dist, emitters.probability[e] / g[12] * dist * dist / cos_l, e, b1, b2


@inlined
def pdf_li(emitters, triangle, d, t):
    """Solid-angle density of ``sample_li`` for a ray along ``d`` hitting ``triangle`` at distance ``t``."""
    e = emitters.of_triangle[triangle]
    if e < 0:
        return 0.0
    g = emitters.geometry[e]
    cos_l = abs(d[0] * g[9] + d[1] * g[10] + d[2] * g[11])
    if cos_l <= 0.0:
        return 0.0
    return emitters.probability[e] / g[12] * t * t / cos_l


@inlined
def sample_position(emitters, u0, u1, u2):
    """(point, unit geometric normal, area density incl. the triangle's choice, material, emitter index,
    barycentrics b1, b2) of a point on an emissive triangle: where a light path starts."""
    e = pick(emitters, u0)
    g = emitters.geometry[e]
    b1, b2 = uniform_triangle(u1, u2)
    p = (g[0] + b1 * g[3] + b2 * g[6], g[1] + b1 * g[4] + b2 * g[7], g[2] + b1 * g[5] + b2 * g[8])
    return p, (g[9], g[10], g[11]), emitters.probability[e] / g[12], emitters.material[e], e, b1, b2
