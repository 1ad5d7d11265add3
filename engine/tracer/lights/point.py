"""Point and spot lights, optionally with a radius (then a sphere light).

Units as Cycles: power P gives intensity I = P / (4π) W/sr (spots too, cut by Blender's smoothstep
cone falloff). With radius r > 0 it is a sphere of radiance I / (π r²), hit by rays and sampled
uniformly in the cone it subtends.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from ..vec3 import tangents, to_world
from ..warps import uniform_cone, uniform_sphere
from .row import (L_CAMERA, L_COS_HALF, L_KIND, L_NX, L_NY, L_NZ, L_PX, L_PY, L_PZ, L_RADIUS, L_SCALE, L_SMOOTH,
                  L_SPECTRUM, L_SPOT, LIGHT_ROW, POINT, SPHERE)


def point_row(light, spectrum_id, offset):
    """The row of a ``scene.Light`` of kind point or spot (``offset``: the camera position, m)."""
    row = np.zeros(LIGHT_ROW)
    radius = float(max(light.radius_m, 0.0))
    intensity = float(light.power_w) / (4.0 * math.pi)
    row[L_KIND] = SPHERE if radius > 0 else POINT
    row[L_SPECTRUM] = spectrum_id
    row[L_SCALE] = intensity / (math.pi * radius * radius) if radius > 0 else intensity
    row[L_PX:L_PZ + 1] = np.asarray(light.position, np.float64) - offset
    axis = np.asarray(light.direction, np.float64)
    row[L_NX:L_NZ + 1] = axis / np.linalg.norm(axis)
    row[L_RADIUS] = radius
    row[L_SPOT] = 1.0 if light.kind == "spot" else 0.0
    row[L_COS_HALF] = math.cos(min(light.spot_size_rad, math.pi) / 2.0)
    row[L_SMOOTH] = (1.0 - row[L_COS_HALF]) * float(np.clip(light.spot_blend, 0.0, 1.0))
    row[L_CAMERA] = 1.0 if light.visible_camera and radius > 0 else 0.0
    return row


def point_power(row) -> float:
    """Radiant power (W, luminance-normalised spectrum) for light selection."""
    intensity = row[L_SCALE] * (math.pi * row[L_RADIUS] ** 2 if row[L_KIND] == SPHERE else 1.0)
    return 4.0 * math.pi * intensity


@kernel
def spot_falloff(row, px, py, pz):
    """Blender's spot falloff at point p: 0 outside the cone, smoothstep over the blend region."""
    if row[L_SPOT] == 0.0:
        return 1.0
    dx, dy, dz = px - row[L_PX], py - row[L_PY], pz - row[L_PZ]
    dist = math.sqrt(dx * dx + dy * dy + dz * dz)
    cos_a = (dx * row[L_NX] + dy * row[L_NY] + dz * row[L_NZ]) / dist if dist > 0.0 else 1.0
    smooth = row[L_SMOOTH]
    if smooth <= 0.0:
        return 1.0 if cos_a > row[L_COS_HALF] else 0.0
    x = min(max((cos_a - row[L_COS_HALF]) / smooth, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


@kernel
def sphere_hit_distance(row, o, d):
    """Distance along the ray to the sphere (inf: miss, or the origin inside it)."""
    ox, oy, oz = o[0] - row[L_PX], o[1] - row[L_PY], o[2] - row[L_PZ]
    b = ox * d[0] + oy * d[1] + oz * d[2]
    c = ox * ox + oy * oy + oz * oz - row[L_RADIUS] * row[L_RADIUS]
    disc = b * b - c
    if disc < 0.0 or c <= 0.0:
        return math.inf
    root = math.sqrt(disc)
    t = -b - root
    if t <= 0.0:
        t = -b + root
    return t if t > 0.0 else math.inf


@kernel
def _one_minus_cos(row, p):
    dx, dy, dz = row[L_PX] - p[0], row[L_PY] - p[1], row[L_PZ] - p[2]
    dist = math.sqrt(dx * dx + dy * dy + dz * dz)
    sin2 = min((row[L_RADIUS] / max(dist, 1e-300)) ** 2, 1.0)
    return sin2 / (1.0 + math.sqrt(1.0 - sin2)), dist, (dx, dy, dz)


@kernel
def sample_li(row, p, u1, u2):
    """(wi, distance, pdf (1 for the delta point), radiance factor) toward the light from ``p``."""
    falloff = spot_falloff(row, p[0], p[1], p[2])
    if row[L_KIND] == POINT:
        dx, dy, dz = row[L_PX] - p[0], row[L_PY] - p[1], row[L_PZ] - p[2]
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)
        if dist <= 0.0:
            return (0.0, 0.0, 1.0), 0.0, 0.0, 0.0
        return (dx / dist, dy / dist, dz / dist), dist, 1.0, row[L_SCALE] * falloff / (dist * dist)
    omc, dist_c, to_c = _one_minus_cos(row, p)
    if not dist_c > row[L_RADIUS]:
        return (0.0, 0.0, 1.0), 0.0, 0.0, 0.0
    axis = (to_c[0] / dist_c, to_c[1] / dist_c, to_c[2] / dist_c)
    s, t = tangents(axis)
    wi = to_world(uniform_cone(u1, u2, 1.0 - omc), s, t, axis)
    dist = sphere_hit_distance(row, p, wi)
    if not math.isfinite(dist):
        return wi, 0.0, 0.0, 0.0
    return wi, dist, 1.0 / (2.0 * math.pi * max(omc, 1e-300)), row[L_SCALE] * falloff


@kernel
def pdf_li(row, o, d, t):
    """Solid-angle density of ``sample_li`` from ``o`` for a direction that hits the sphere."""
    omc, _, _ = _one_minus_cos(row, o)
    return 1.0 / (2.0 * math.pi * max(omc, 1e-300))


@kernel
def le(row, o, d, t):
    """Radiance factor seen along a ray from ``o`` that hits the sphere."""
    return row[L_SCALE] * spot_falloff(row, o[0], o[1], o[2])


@kernel
def sample_position(row, u1, u2):
    """(start of a light path, its outward normal ((0, 0, 0) for a point), area density (1 for the
    point's delta position)): a uniform point on a sphere light."""
    if row[L_KIND] == POINT:
        return (row[L_PX], row[L_PY], row[L_PZ]), (0.0, 0.0, 0.0), 1.0
    n = uniform_sphere(u1, u2)
    r = row[L_RADIUS]
    return ((row[L_PX] + r * n[0], row[L_PY] + r * n[1], row[L_PZ] + r * n[2]), n,
            1.0 / (4.0 * math.pi * r * r))


@kernel
def emitted(row, n, d):
    """Intensity of a point (W/sr), or radiance × cos of a sphere's surface with normal ``n``, along
    ``d``; without the spot falloff, which depends on the receiving point (``spot_falloff``)."""
    if row[L_KIND] == POINT:
        return row[L_SCALE]
    cos_l = d[0] * n[0] + d[1] * n[1] + d[2] * n[2]
    return row[L_SCALE] * cos_l if cos_l > 0.0 else 0.0
