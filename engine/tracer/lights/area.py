"""Area lights: rectangle or disk (ellipse), one-sided, emitting along their normal (the light's -Z).

Power P over area A gives radiance P / (π A) (Cycles' convention). Sampled uniformly by area and
converted to solid angle; rays that hit the front face see it, the back is invisible.

Spread (Cycles'): a soft-box grid of slats narrows the beam to a half-angle a; radiance at angle θ
from the normal is multiplied by (tan a - tan θ) / (tan a - a) (0 beyond a), which keeps the power:
∫₀ᵃ cos θ (tan a - tan θ) / (tan a - a) 2π sin θ dθ = π. (A spread of π leaves the light Lambertian.)
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from ..warps import concentric_disk
from .row import (DISK, L_AREA, L_CAMERA, L_HALF_U, L_HALF_V, L_KIND, L_NX, L_NY, L_NZ, L_PX, L_PY, L_PZ, L_SCALE,
                  L_SPECTRUM, L_SPREAD_NORM, L_SPREAD_TAN, L_UX, L_UY, L_UZ, L_VX, L_VY, L_VZ, LIGHT_ROW, RECTANGLE)

MIN_HALF_SPREAD = 1e-3  # rad: a narrower beam is a collimated one, which no light sample finds


def area_row(light, spectrum_id, offset):
    """The row of an area ``scene.Light`` (``offset``: the camera position, m)."""
    row = np.zeros(LIGHT_ROW)
    normal = np.asarray(light.direction, np.float64)
    normal = normal / np.linalg.norm(normal)
    u = np.asarray(light.axis_u, np.float64)
    u = u - normal * (u @ normal)
    u = u / np.linalg.norm(u)
    v = np.cross(normal, u)
    if np.asarray(light.axis_v, np.float64) @ v < 0:
        v = -v
    disk = light.area_shape == "disk"
    half_u, half_v = 0.5 * float(light.size_u_m), 0.5 * float(light.size_v_m)
    area = (math.pi if disk else 4.0) * half_u * half_v
    row[L_KIND] = DISK if disk else RECTANGLE
    row[L_SPECTRUM] = spectrum_id
    row[L_SCALE] = float(light.power_w) / (math.pi * area) if area > 0 else 0.0
    row[L_PX:L_PZ + 1] = np.asarray(light.position, np.float64) - offset
    row[L_NX:L_NZ + 1] = normal
    row[L_UX:L_UZ + 1] = u
    row[L_VX:L_VZ + 1] = v
    row[L_HALF_U], row[L_HALF_V], row[L_AREA] = half_u, half_v, area
    row[L_CAMERA] = 1.0 if light.visible_camera else 0.0
    half = 0.5 * float(light.spread_rad)
    if half < 0.5 * math.pi - 1e-9:
        half = max(half, MIN_HALF_SPREAD)
        row[L_SPREAD_TAN] = math.tan(half)
        # tan a - a loses its digits for small a: its series a³/3 + 2a⁵/15 there.
        row[L_SPREAD_NORM] = 1.0 / (math.tan(half) - half) if half > 0.05 else 1.0 / (half**3 / 3 + 2 * half**5 / 15)
    return row


@kernel
def spread_factor(row, cos_l):
    """Radiance factor of the spread at cos θ = ``cos_l`` from the normal (1 without a spread)."""
    if row[L_SPREAD_TAN] == 0.0:
        return 1.0
    if not cos_l > 0.0:
        return 0.0
    tan_l = math.sqrt(max(1.0 - cos_l * cos_l, 0.0)) / cos_l
    return max(row[L_SPREAD_TAN] - tan_l, 0.0) * row[L_SPREAD_NORM]


def area_power(row) -> float:
    return row[L_SCALE] * math.pi * row[L_AREA]


@kernel
def sample_li(row, p, u1, u2):
    """(wi, distance, solid-angle pdf, radiance factor) for a uniform point on the light."""
    if row[L_KIND] == DISK:
        x, y = concentric_disk(u1, u2)
    else:
        x, y = 2.0 * u1 - 1.0, 2.0 * u2 - 1.0
    su, sv = x * row[L_HALF_U], y * row[L_HALF_V]
    wx = row[L_PX] + su * row[L_UX] + sv * row[L_VX] - p[0]
    wy = row[L_PY] + su * row[L_UY] + sv * row[L_VY] - p[1]
    wz = row[L_PZ] + su * row[L_UZ] + sv * row[L_VZ] - p[2]
    dist = math.sqrt(wx * wx + wy * wy + wz * wz)
    if dist <= 0.0:
        return (0.0, 0.0, 1.0), 0.0, 0.0, 0.0
    wi = (wx / dist, wy / dist, wz / dist)
    cos_l = -(wi[0] * row[L_NX] + wi[1] * row[L_NY] + wi[2] * row[L_NZ])
    if cos_l <= 0.0:
        return wi, dist, 0.0, 0.0
    return wi, dist, dist * dist / (row[L_AREA] * cos_l), row[L_SCALE] * spread_factor(row, cos_l)


@kernel
def intersect(row, o, d):
    """Distance to the front face along the ray (inf: miss or back face)."""
    denom = d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ]
    if denom >= 0.0:
        return math.inf
    t = ((row[L_PX] - o[0]) * row[L_NX] + (row[L_PY] - o[1]) * row[L_NY] + (row[L_PZ] - o[2]) * row[L_NZ]) / denom
    if not t > 0.0:
        return math.inf
    qx, qy, qz = o[0] + t * d[0] - row[L_PX], o[1] + t * d[1] - row[L_PY], o[2] + t * d[2] - row[L_PZ]
    x = (qx * row[L_UX] + qy * row[L_UY] + qz * row[L_UZ]) / row[L_HALF_U]
    y = (qx * row[L_VX] + qy * row[L_VY] + qz * row[L_VZ]) / row[L_HALF_V]
    if row[L_KIND] == DISK:
        inside = x * x + y * y <= 1.0
    else:
        inside = abs(x) <= 1.0 and abs(y) <= 1.0
    return t if inside else math.inf


@kernel
def pdf_li(row, o, d, t):
    cos_l = abs(d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ])
    return t * t / (row[L_AREA] * max(cos_l, 1e-300))


@kernel
def le(row, o, d, t):
    return row[L_SCALE] * spread_factor(row, -(d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ]))


@kernel
def sample_position(row, u1, u2):
    """(uniform point on the light, area density 1/m²): where a light path starts."""
    if row[L_KIND] == DISK:
        x, y = concentric_disk(u1, u2)
    else:
        x, y = 2.0 * u1 - 1.0, 2.0 * u2 - 1.0
    su, sv = x * row[L_HALF_U], y * row[L_HALF_V]
    return ((row[L_PX] + su * row[L_UX] + sv * row[L_VX], row[L_PY] + su * row[L_UY] + sv * row[L_VY],
             row[L_PZ] + su * row[L_UZ] + sv * row[L_VZ]), 1.0 / row[L_AREA])


@kernel
def emitted(row, d):
    """Radiance factor × cos to the normal leaving the light along ``d`` (front face only)."""
    cos_l = d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ]
    return row[L_SCALE] * spread_factor(row, cos_l) * cos_l if cos_l > 0.0 else 0.0
