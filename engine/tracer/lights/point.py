"""Point and spot lights, optionally with a radius (then a sphere light, or Cycles' soft falloff).

Units as Cycles: power P gives intensity I = P / (4π) W/sr (spots too, cut by Blender's smoothstep
cone falloff). With radius r > 0 the light has radiance I / (π r²) and is, as Cycles 4.x models it:

- with Soft Falloff (Blender's default, ``L_SOFT``): a disc of radius r at the light's centre that
  always faces the point it lights (and the ray that looks at it). Irradiance on axis is
  I / (d² + r²) instead of I / d²: no sharp edge where the light's sphere cuts a surface, and a
  surface inside that sphere is lit (at most I / r²);
- without it: a sphere, sampled uniformly in the cone it subtends; a point inside it sees its
  radiance all around (irradiance π · radiance = I / r²), sampled over all directions.

A spot's cone falloff is taken along each sampled direction from the light's disc or sphere (as
Cycles), so a radius widens the cone's edge.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from ..vec3 import tangents, to_world
from ..warps import concentric_disk, uniform_cone, uniform_sphere
from .row import (L_CAMERA, L_COS_HALF, L_KIND, L_NX, L_NY, L_NZ, L_PX, L_PY, L_PZ, L_RADIUS, L_SCALE, L_SMOOTH,
                  L_SOFT, L_SPECTRUM, L_SPOT, LIGHT_ROW, POINT, SPHERE)


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
    row[L_SOFT] = 1.0 if light.soft_falloff and radius > 0 else 0.0
    return row


def point_power(row) -> float:
    """Radiant power (W, luminance-normalised spectrum) for light selection."""
    intensity = row[L_SCALE] * (math.pi * row[L_RADIUS] ** 2 if row[L_KIND] == SPHERE else 1.0)
    return 4.0 * math.pi * intensity


@kernel
def spot_attenuation(row, ex, ey, ez):
    """Blender's spot falloff of light leaving along the unit direction e: 0 outside the cone,
    smoothstep over the blend region (1 for point lights)."""
    if row[L_SPOT] == 0.0:
        return 1.0
    cos_a = ex * row[L_NX] + ey * row[L_NY] + ez * row[L_NZ]
    smooth = row[L_SMOOTH]
    if smooth <= 0.0:
        return 1.0 if cos_a > row[L_COS_HALF] else 0.0
    x = min(max((cos_a - row[L_COS_HALF]) / smooth, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


@kernel
def spot_falloff(row, px, py, pz):
    """Blender's spot falloff at point p seen from the light's centre: 0 outside the cone, smoothstep
    over the blend region."""
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
    """Distance along the ray to the sphere (inf: miss); from inside it, where the ray leaves it (Cycles
    lights what lies inside a sphere light)."""
    ox, oy, oz = o[0] - row[L_PX], o[1] - row[L_PY], o[2] - row[L_PZ]
    b = ox * d[0] + oy * d[1] + oz * d[2]
    c = ox * ox + oy * oy + oz * oz - row[L_RADIUS] * row[L_RADIUS]
    disc = b * b - c
    if disc < 0.0:
        return math.inf
    root = math.sqrt(disc)
    t = -b - root
    if t <= 0.0:
        t = -b + root
    return t if t > 0.0 else math.inf


@kernel
def soft_disc_hit_distance(row, o, d):
    """Distance along the ray to the soft-falloff disc, which faces the ray's origin (inf: miss)."""
    nx, ny, nz = o[0] - row[L_PX], o[1] - row[L_PY], o[2] - row[L_PZ]
    dist_c = math.sqrt(nx * nx + ny * ny + nz * nz)
    toward = -(nx * d[0] + ny * d[1] + nz * d[2])  # dist_c × the cosine between the ray and the disc normal
    if not (dist_c > 0.0 and toward > 0.0):
        return math.inf
    t = dist_c * dist_c / toward
    hx, hy, hz = nx + t * d[0], ny + t * d[1], nz + t * d[2]
    return t if hx * hx + hy * hy + hz * hz <= row[L_RADIUS] * row[L_RADIUS] else math.inf


@kernel
def hit_distance(row, o, d):
    """Distance along the ray to the light's sphere, or its soft-falloff disc (inf: miss)."""
    if row[L_SOFT] != 0.0:
        return soft_disc_hit_distance(row, o, d)
    return sphere_hit_distance(row, o, d)


@kernel
def _soft_disc_pdf(row, o, d, t):
    """Solid-angle density of sampling the soft-falloff disc uniformly, toward ``d`` at distance ``t``."""
    nx, ny, nz = o[0] - row[L_PX], o[1] - row[L_PY], o[2] - row[L_PZ]
    dist_c = math.sqrt(nx * nx + ny * ny + nz * nz)
    cos_l = -(nx * d[0] + ny * d[1] + nz * d[2]) / max(dist_c, 1e-300)
    r = row[L_RADIUS]
    return t * t / (math.pi * r * r * max(cos_l, 1e-300))


@kernel
def _sample_soft_disc(row, p, u1, u2):
    """(wi, distance, solid-angle pdf, radiance factor) toward a uniform point of the disc facing ``p``."""
    nx, ny, nz = p[0] - row[L_PX], p[1] - row[L_PY], p[2] - row[L_PZ]
    dist_c = math.sqrt(nx * nx + ny * ny + nz * nz)
    if not dist_c > 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0, 0.0
    normal = (nx / dist_c, ny / dist_c, nz / dist_c)
    s, t = tangents(normal)
    x, y = concentric_disk(u1, u2)
    r = row[L_RADIUS]
    wx = row[L_PX] + r * (x * s[0] + y * t[0]) - p[0]
    wy = row[L_PY] + r * (x * s[1] + y * t[1]) - p[1]
    wz = row[L_PZ] + r * (x * s[2] + y * t[2]) - p[2]
    dist = math.sqrt(wx * wx + wy * wy + wz * wz)
    wi = (wx / dist, wy / dist, wz / dist)
    # the disc's normal is p's direction from the centre: its cosine toward p is dist_c / dist
    pdf = dist * dist * dist / (math.pi * r * r * dist_c)
    return wi, dist, pdf, row[L_SCALE] * spot_attenuation(row, -wi[0], -wi[1], -wi[2])


@kernel
def _one_minus_cos(row, p):
    dx, dy, dz = row[L_PX] - p[0], row[L_PY] - p[1], row[L_PZ] - p[2]
    dist = math.sqrt(dx * dx + dy * dy + dz * dz)
    sin2 = min((row[L_RADIUS] / max(dist, 1e-300)) ** 2, 1.0)
    return sin2 / (1.0 + math.sqrt(1.0 - sin2)), dist, (dx, dy, dz)


@kernel
def sample_li(row, p, u1, u2):
    """(wi, distance, pdf (1 for the delta point), radiance factor) toward the light from ``p``."""
    if row[L_KIND] == POINT:
        dx, dy, dz = row[L_PX] - p[0], row[L_PY] - p[1], row[L_PZ] - p[2]
        dist = math.sqrt(dx * dx + dy * dy + dz * dz)
        if dist <= 0.0:
            return (0.0, 0.0, 1.0), 0.0, 0.0, 0.0
        falloff = spot_falloff(row, p[0], p[1], p[2])
        return (dx / dist, dy / dist, dz / dist), dist, 1.0, row[L_SCALE] * falloff / (dist * dist)
    if row[L_SOFT] != 0.0:
        return _sample_soft_disc(row, p, u1, u2)
    omc, dist_c, to_c = _one_minus_cos(row, p)
    if not dist_c > row[L_RADIUS]:  # inside: the sphere is all around, uniform directions (no spot cone, as Cycles)
        wi = uniform_sphere(u1, u2)
        dist = sphere_hit_distance(row, p, wi)
        if not math.isfinite(dist):
            return wi, 0.0, 0.0, 0.0
        return wi, dist, 1.0 / (4.0 * math.pi), row[L_SCALE]
    axis = (to_c[0] / dist_c, to_c[1] / dist_c, to_c[2] / dist_c)
    s, t = tangents(axis)
    wi = to_world(uniform_cone(u1, u2, 1.0 - omc), s, t, axis)
    dist = sphere_hit_distance(row, p, wi)
    if not math.isfinite(dist):
        return wi, 0.0, 0.0, 0.0
    falloff = spot_attenuation(row, -wi[0], -wi[1], -wi[2])
    return wi, dist, 1.0 / (2.0 * math.pi * max(omc, 1e-300)), row[L_SCALE] * falloff


@kernel
def pdf_li(row, o, d, t):
    """Solid-angle density of ``sample_li`` from ``o`` for a direction that hits the sphere (or the
    soft-falloff disc) at distance ``t``."""
    if row[L_SOFT] != 0.0:
        return _soft_disc_pdf(row, o, d, t)
    omc, dist_c, _ = _one_minus_cos(row, o)
    if not dist_c > row[L_RADIUS]:
        return 1.0 / (4.0 * math.pi)
    return 1.0 / (2.0 * math.pi * max(omc, 1e-300))


@kernel
def le(row, o, d, t):
    """Radiance factor seen along a ray from ``o`` that hits the sphere (or the soft-falloff disc); from
    inside the sphere, without the spot cone (as Cycles)."""
    if row[L_SOFT] == 0.0:
        ox, oy, oz = o[0] - row[L_PX], o[1] - row[L_PY], o[2] - row[L_PZ]
        if ox * ox + oy * oy + oz * oz <= row[L_RADIUS] * row[L_RADIUS]:
            return row[L_SCALE]
    return row[L_SCALE] * spot_attenuation(row, -d[0], -d[1], -d[2])


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
