"""Sun: a distant light of irradiance E (Blender's Strength, W/m²) on a surface facing it. With angular
diameter 2θ > 0 it is a uniform disc of radiance E / (π sin²θ), sampled uniformly in its cone and seen
by escaping rays; with angle 0 it is a delta direction. A sky's Sun (``environment``) darkens toward
its limb: radiance × (1 - L_LIMB (1 - μ)), μ = sqrt(1 - (γ/θ)²) at angle γ from the centre."""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from ..vec3 import tangents, to_world
from ..warps import uniform_cone
from .row import (L_CAMERA, L_COS_MAX, L_KIND, L_LIMB, L_NX, L_NY, L_NZ, L_ONE_MINUS_COS, L_SCALE, L_SPECTRUM, LIGHT_ROW, SUN,
                  SUN_DISK)


def sun_row(light, spectrum_id):
    """The row of a sun ``scene.Light``."""
    row = np.zeros(LIGHT_ROW)
    d = np.asarray(light.direction, np.float64)
    row[L_NX:L_NZ + 1] = -d / np.linalg.norm(d)
    row[L_SPECTRUM] = spectrum_id
    irradiance = float(light.irradiance_w_m2)
    half = min(0.5 * float(max(light.sun_angle_rad, 0.0)), math.pi / 2)
    if half <= 0.0:
        row[L_KIND], row[L_SCALE] = SUN, irradiance
        return row
    row[L_KIND] = SUN_DISK
    row[L_CAMERA] = 1.0 if light.visible_camera else 0.0
    row[L_ONE_MINUS_COS] = 2.0 * math.sin(half / 2.0) ** 2
    row[L_COS_MAX] = 1.0 - row[L_ONE_MINUS_COS]
    row[L_SCALE] = irradiance / (math.pi * math.sin(half) ** 2)
    return row


def sun_power(row, scene_radius_m) -> float:
    """Power through the scene's bounding disc of radius ``scene_radius_m``, for light selection."""
    irradiance = row[L_SCALE] if row[L_KIND] == SUN else row[L_SCALE] * math.pi * (1 - row[L_COS_MAX] ** 2)
    return irradiance * math.pi * max(scene_radius_m, 1e-3) ** 2


@kernel
def _limb(row, cos_gamma):
    """Limb darkening at cos γ from the disc's centre (1 without it)."""
    if row[L_LIMB] == 0.0:
        return 1.0
    r2 = min(max((1.0 - cos_gamma) / row[L_ONE_MINUS_COS], 0.0), 1.0)  # (γ/θ)² for small discs
    return 1.0 - row[L_LIMB] * (1.0 - math.sqrt(1.0 - r2))


@kernel
def sample_li(row, p, u1, u2):
    """(wi, distance (inf), pdf (1 for the delta sun), radiance or irradiance factor)."""
    to_sun = (row[L_NX], row[L_NY], row[L_NZ])
    if row[L_KIND] == SUN:
        return to_sun, math.inf, 1.0, row[L_SCALE]
    s, t = tangents(to_sun)
    local = uniform_cone(u1, u2, row[L_COS_MAX])
    wi = to_world(local, s, t, to_sun)
    return wi, math.inf, 1.0 / (2.0 * math.pi * row[L_ONE_MINUS_COS]), row[L_SCALE] * _limb(row, local[2])


@kernel
def pdf_escaped(row, d):
    if d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ] >= row[L_COS_MAX]:
        return 1.0 / (2.0 * math.pi * row[L_ONE_MINUS_COS])
    return 0.0


@kernel
def le_escaped(row, d):
    """Radiance factor along an escaping ray (0 outside the disc)."""
    cos_gamma = d[0] * row[L_NX] + d[1] * row[L_NY] + d[2] * row[L_NZ]
    if cos_gamma >= row[L_COS_MAX]:
        return row[L_SCALE] * _limb(row, cos_gamma)
    return 0.0


@kernel
def sample_emission_direction(row, u1, u2):
    """(unit direction the sunlight travels, solid-angle pdf (1 for the delta sun), radiance (disc) or
    irradiance (delta) factor across the beam)."""
    to_sun = (row[L_NX], row[L_NY], row[L_NZ])
    if row[L_KIND] == SUN:
        return (-to_sun[0], -to_sun[1], -to_sun[2]), 1.0, row[L_SCALE]
    s, t = tangents(to_sun)
    w = to_world(uniform_cone(u1, u2, row[L_COS_MAX]), s, t, to_sun)
    return (-w[0], -w[1], -w[2]), 1.0 / (2.0 * math.pi * row[L_ONE_MINUS_COS]), row[L_SCALE]
