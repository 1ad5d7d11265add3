"""How large each light looks from the specular objects: the scene analysis's measure of whether path
tracing can find a light's caustics by itself.

A camera path finds a caustic only if, after the specular object, it happens to hit the light: likely
for a large light (a 0.5 m softbox 1.6 m from a glass ball subtends 0.1 sr), hopeless for a slit or a
small bulb, impossible for a point, spot or delta sun. ``small_lights`` names the lights that reach a
specular object and subtend less than ``SMALL_SOLID_ANGLE_SR`` from it (delta lights always); the
analysis turns light tracing on for them (``analysis.choose_light_tracing``).
"""

from __future__ import annotations

import math

import numpy as np

from .row import (DISK, L_AREA, L_COS_HALF, L_KIND, L_NX, L_NZ, L_ONE_MINUS_COS, L_PX, L_PZ, L_RADIUS, L_SPOT,
                  MESH, POINT, RECTANGLE, SPHERE, SUN, SUN_DISK)

SMALL_SOLID_ANGLE_SR = 0.01  # a 10 cm square light 1 m away


def _solid_angle(row, mesh, centre, radius):
    """Solid angle (sr) of the light seen from the target sphere (centre, radius); 0 if it cannot
    light the sphere, inf for delta lights."""
    kind = int(row[L_KIND])
    to_light = row[L_PX:L_PZ + 1] - centre
    distance = max(float(np.linalg.norm(to_light)), radius, 1e-9)
    if kind == SUN:
        return math.inf
    if kind == SUN_DISK:
        return 2.0 * math.pi * row[L_ONE_MINUS_COS]
    if kind == POINT or kind == SPHERE:
        if row[L_SPOT]:
            axis = row[L_NX:L_NZ + 1]
            cos_axis = float(-to_light @ axis) / distance
            if math.acos(np.clip(cos_axis, -1, 1)) > math.acos(row[L_COS_HALF]) + math.asin(min(radius / distance, 1)):
                return 0.0
        return math.inf if kind == POINT else math.pi * row[L_RADIUS] ** 2 / distance ** 2
    if kind == RECTANGLE or kind == DISK:
        cos_l = float(-to_light @ row[L_NX:L_NZ + 1]) / distance
        if cos_l <= -radius / distance:
            return 0.0  # the sphere lies behind the light
        return row[L_AREA] * max(cos_l, radius / distance) / distance ** 2
    if kind == MESH and len(mesh.geometry):
        g = mesh.geometry
        centres = g[:, 0:3] + (g[:, 3:6] + g[:, 6:9]) / 3.0
        w = centres - centre
        d2 = np.maximum((w * w).sum(1), radius * radius)
        cos_l = np.abs((w * g[:, 9:12]).sum(1)) / np.sqrt(d2)
        return float((g[:, 12] * cos_l / d2).sum())
    return 0.0


def small_lights(light_rows, names, mesh, targets) -> list[str]:
    """Names of the lights that reach some target sphere and look smaller than ``SMALL_SOLID_ANGLE_SR``
    from it (suns and other delta lights always: path tracing never finds their caustics)."""
    small = []
    for row, name in zip(light_rows, names):
        for centre, radius in zip(targets.spheres[:, :3], targets.spheres[:, 3]):
            omega = _solid_angle(row, mesh, centre, radius)
            if 0.0 < omega < SMALL_SOLID_ANGLE_SR or math.isinf(omega):
                small.append(name)
                break
    return small
