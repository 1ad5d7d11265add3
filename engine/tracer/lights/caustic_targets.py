"""Where light paths are aimed: bounding spheres of the purely specular objects.

A light path only contributes (``stages.light_paths``) if its first hit is a purely specular
material (``MAT_DELTA``): a path that first meets a diffuse surface is light sampling's business. So
emission is sampled toward the specular objects only, like the projection maps of photon mapping: a
direction leaving a point is drawn from the cones the spheres subtend (a sphere picked ∝ its solid
angle, then uniformly in its cone), a point of a distant light's beam from the discs the spheres
project (picked ∝ area). Every direction that reaches a specular object lies in its sphere's cone,
so the estimate stays unbiased.

``CausticTargets``: ``spheres`` float64 [S, 4] (centre, radius; camera-relative metres), ``centre`` and
``radius`` of the whole geometry's bounding sphere (where a distant light's rays start).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined
from ..vec3 import tangents, to_world
from ..warps import concentric_disk, uniform_cone

CausticTargets = namedtuple("CausticTargets", "spheres centre radius")

MAX_TARGETS = 64  # beyond this, objects are grouped by material (the pdf loops over every sphere)
_RADIUS_MARGIN = 1e-6  # relative: float32 vertices must stay inside their sphere


def _bounding_sphere(points):
    centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
    radius = float(np.sqrt(((points - centre) ** 2).sum(axis=1).max()))
    return np.array([*centre, radius * (1.0 + _RADIUS_MARGIN) + _RADIUS_MARGIN * float(np.abs(centre).max())])


def _groups(triangles, keys):
    """Triangle indices per distinct key (in key order)."""
    order = np.argsort(keys, kind="stable")
    sorted_keys = keys[order]
    cuts = np.flatnonzero(np.diff(sorted_keys)) + 1
    return np.split(triangles[order], cuts)


def _at_every_step(still, steps) -> np.ndarray:
    """float64 [S, N, W]: rows ``still`` [N, W] and, with motion blur, where they are at the shutter's steps
    (``steps`` [S, N, W]; empty when they do not move), so a sphere around them holds them all shutter long."""
    still = np.asarray(still, np.float64)
    steps = np.asarray(steps, np.float64)
    if not steps.shape[0] or steps.shape[1] != still.shape[0]:
        return still[None]
    return np.concatenate([still[None], steps])


def build_caustic_targets(geometry, material_flags, delta_flag, triangle_object=None) -> CausticTargets:
    """Spheres around the triangles whose material has ``delta_flag`` in ``material_flags``: one per
    object (``triangle_object`` [T], rows of ``geometry``), else per material; one sphere for them all if
    that still leaves more than ``MAX_TARGETS``. Empty when no material is purely specular. With motion blur each
    sphere holds its triangles at every time step of the shutter."""
    moving = _at_every_step(geometry.vertices, geometry.motion)
    vertices = moving.reshape(-1, 3)
    points = np.concatenate([_at_every_step(geometry.spheres, geometry.sphere_motion).reshape(-1, 4),
                             _at_every_step(geometry.curves, geometry.curve_motion).reshape(-1, 4)])
    extent = np.concatenate([vertices, points[:, :3] - points[:, 3:], points[:, :3] + points[:, 3:]])
    if len(extent):
        lo, hi = extent.min(axis=0), extent.max(axis=0)
        centre = 0.5 * (lo + hi)
        radius = float(np.linalg.norm(hi - lo)) * 0.5 + 1e-3
    else:
        centre, radius = np.zeros(3), 1.0
    materials = np.asarray(geometry.material)[:len(geometry.triangles)]
    specular = np.flatnonzero(np.asarray(material_flags)[materials] & delta_flag) if len(materials) else []
    spheres = np.zeros((0, 4))
    if len(specular):
        keys = materials[specular].astype(np.int64)
        if triangle_object is not None:
            keys = np.asarray(triangle_object, np.int64)[specular] * (int(materials.max()) + 1) + keys
        groups = _groups(specular, keys)
        if len(groups) > MAX_TARGETS:
            groups = _groups(specular, materials[specular].astype(np.int64))
        if len(groups) > MAX_TARGETS:
            groups = [specular]
        triangles = np.asarray(geometry.triangles)
        spheres = np.array([_bounding_sphere(moving[:, triangles[g]].reshape(-1, 3)) for g in groups])
    spheres = _with_specular_points(geometry, material_flags, delta_flag, spheres)
    return CausticTargets(np.ascontiguousarray(spheres), np.ascontiguousarray(centre, np.float64), radius)


def _with_specular_points(geometry, material_flags, delta_flag, spheres):
    """``spheres`` and one more around the point-cloud spheres (``Geometry.spheres``) whose material is
    purely specular, so light paths aim at glass and mirror points too."""
    points = _at_every_step(geometry.spheres, geometry.sphere_motion)
    if not points.shape[1]:
        return spheres
    materials = np.asarray(geometry.material)[len(geometry.triangles):len(geometry.triangles) + points.shape[1]]
    specular = points[:, (np.asarray(material_flags)[materials] & delta_flag) != 0].reshape(-1, 4)
    if not len(specular):
        return spheres
    lo = (specular[:, :3] - specular[:, 3:]).min(axis=0)
    hi = (specular[:, :3] + specular[:, 3:]).max(axis=0)
    around = np.concatenate([0.5 * (lo + hi), [0.5 * float(np.linalg.norm(hi - lo)) + 1e-3]])
    return np.vstack([np.reshape(spheres, (-1, 4)), around[None]])


@inlined
def _cone(targets, s, x):
    """(unit axis from ``x`` to sphere ``s``, cos of its half-angle, solid angle); the whole sphere
    of directions when ``x`` is inside."""
    sphere = targets.spheres[s]
    wx, wy, wz = sphere[0] - x[0], sphere[1] - x[1], sphere[2] - x[2]
    d = math.sqrt(wx * wx + wy * wy + wz * wz)
    r = sphere[3]
    if d <= r:
        return (0.0, 0.0, 1.0), -1.0, 4.0 * math.pi
    sin2 = (r / d) * (r / d)
    cos_max = math.sqrt(1.0 - sin2)
    return (wx / d, wy / d, wz / d), cos_max, 2.0 * math.pi * sin2 / (1.0 + cos_max)


@inlined
def _direction_density(targets, x, direction, chosen, total):
    count = 0
    for s in range(targets.spheres.shape[0]):
        if s == chosen:
            count += 1
            continue
        axis, cos_max, _ = _cone(targets, s, x)
        if direction[0] * axis[0] + direction[1] * axis[1] + direction[2] * axis[2] >= cos_max:
            count += 1
    return count / total


@inlined
def direction_pdf(targets, x, direction):
    """Solid-angle density of ``sample_direction`` from ``x`` (1/sr)."""
    total = 0.0
    for s in range(targets.spheres.shape[0]):
        total += _cone(targets, s, x)[2]
    if not total > 0.0:
        return 0.0
    return _direction_density(targets, x, direction, -1, total)


@inlined
def sample_direction(targets, x, u0, u1, u2):
    """(unit direction, solid-angle pdf) from ``x`` toward the specular objects."""
    count = targets.spheres.shape[0]
    total = 0.0
    for s in range(count):
        total += _cone(targets, s, x)[2]
    target = u0 * total
    chosen = count - 1
    below = 0.0
    for s in range(count):
        omega = _cone(targets, s, x)[2]
        if target < below + omega:
            chosen = s
            break
        below += omega
    axis, cos_max, _ = _cone(targets, chosen, x)
    s_axis, t_axis = tangents(axis)
    direction = to_world(uniform_cone(u1, u2, cos_max), s_axis, t_axis, axis)
    return direction, _direction_density(targets, x, direction, chosen, total)


@inlined
def _inside_disc(targets, s, q, d):
    sphere = targets.spheres[s]
    wx, wy, wz = q[0] - sphere[0], q[1] - sphere[1], q[2] - sphere[2]
    along = wx * d[0] + wy * d[1] + wz * d[2]
    px, py, pz = wx - along * d[0], wy - along * d[1], wz - along * d[2]
    return px * px + py * py + pz * pz <= sphere[3] * sphere[3]


@inlined
def _disc_density(targets, q, d, chosen):
    total = 0.0
    count = 0
    for s in range(targets.spheres.shape[0]):
        total += math.pi * targets.spheres[s, 3] * targets.spheres[s, 3]
        if s == chosen or _inside_disc(targets, s, q, d):
            count += 1
    return count / total if total > 0.0 else 0.0


@inlined
def beam_pdf(targets, q, d):
    """Area density (1/m², across the beam) of ``sample_beam`` for the point ``q`` of a beam along ``d``."""
    return _disc_density(targets, q, d, -1)


@inlined
def sample_beam(targets, d, u0, u1, u2):
    """A ray of a distant light's beam along unit ``d`` that may reach a specular object: (origin, area
    density across the beam (1/m²) of its crossing point). The origin lies before the scene's bounding
    sphere, so the ray meets everything in its way."""
    count = targets.spheres.shape[0]
    total = 0.0
    for s in range(count):
        total += targets.spheres[s, 3] * targets.spheres[s, 3]
    target = u0 * total
    chosen = count - 1
    below = 0.0
    for s in range(count):
        weight = targets.spheres[s, 3] * targets.spheres[s, 3]
        if target < below + weight:
            chosen = s
            break
        below += weight
    sphere = targets.spheres[chosen]
    a, b = tangents(d)
    x, y = concentric_disk(u1, u2)
    x *= sphere[3]
    y *= sphere[3]
    q = (sphere[0] + x * a[0] + y * b[0], sphere[1] + x * a[1] + y * b[1], sphere[2] + x * a[2] + y * b[2])
    c = targets.centre
    back = max((q[0] - c[0]) * d[0] + (q[1] - c[1]) * d[1] + (q[2] - c[2]) * d[2], 0.0) + 1.001 * targets.radius
    origin = (q[0] - back * d[0], q[1] - back * d[1], q[2] - back * d[2])
    return origin, _disc_density(targets, q, d, chosen)
