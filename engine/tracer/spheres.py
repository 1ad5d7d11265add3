"""Spheres: the points of Blender's Point Cloud objects, each a sphere of its own radius.

The export fills ``scene.Scene.points`` (a ``SpherePoints``, world space, float64). ``camera_relative``
turns it into the float32 table Embree and the kernels share (``Geometry.spheres`` [S, 4]: centre minus
the render's origin, radius), as the triangles' vertices are. Spheres are rows of the render's
primitives after the triangles: row T + s is sphere s, so ``Geometry.material`` and ``Geometry.flags``
(and the instance of each row, when node materials read object data) hold T + S entries and every
stage reads a sphere's material the way it reads a triangle's. A sphere hit's (u, v) is its outward
normal as an octahedral code (``embree.queries.closest_hit``), so ``surface_at`` rebuilds the point
exactly on the sphere. With motion blur a sphere's centre and radius at the shutter's time steps
(``motion.Motion.points``) become ``Geometry.sphere_motion``, which Embree and ``sphere_surface`` interpolate
linearly by ray time. Spheres carry no UV map and are not sampled as lights (an emissive sphere is found by
rays, as Cycles finds emissive points).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .jit import inlined
from .octahedral import decode
from .time_steps import row_at


@dataclass
class SpherePoints:
    """``centres`` float64 [S, 3] (world, m), ``radii`` float64 [S] (m), ``material`` int32 [S] (index into
    ``Scene.materials``), ``object`` int32 [S] (index into ``Scene.object_names``), ``instance`` int32 [S]
    (row of ``Scene.surface.instances``, what node materials read as Object Info; None when no material reads
    it), ``pass_index`` float32 [S] (Object ▸ Relations ▸ Pass Index, for the IndexOB pass; None: 0),
    ``random`` float32 [S] (Point Info ▸ Random, uniform in [0, 1]; None: 0) and ``colors`` float32 [A, S, 4]
    (the colour attributes node materials read, slots as ``SurfaceAttributes.colors``, RGBA per point; None:
    none, they read black, alpha 0)."""

    centres: np.ndarray
    radii: np.ndarray
    material: np.ndarray
    object: np.ndarray
    instance: np.ndarray | None = None
    pass_index: np.ndarray | None = None
    random: np.ndarray | None = None
    colors: np.ndarray | None = None

    def __len__(self) -> int:
        return int(len(self.radii))


def no_spheres() -> np.ndarray:
    """``Geometry.spheres`` of a render without point clouds."""
    return np.zeros((0, 4), np.float32)


def no_sphere_motion() -> np.ndarray:
    """``Geometry.sphere_motion`` of a render whose points do not move: empty, so kernels read the frame's."""
    return np.zeros((0, 0, 4), np.float32)


def rendered_rows(points: SpherePoints | None) -> np.ndarray:
    """int64 indices of the points that render: a positive, finite radius (Cycles shows no zero-radius
    point either) and a finite centre."""
    if points is None or not len(points):
        return np.zeros(0, np.int64)
    radii = np.asarray(points.radii, np.float64)
    with np.errstate(invalid="ignore"):
        keep = np.isfinite(radii) & (radii > 0) & np.isfinite(np.asarray(points.centres, np.float64)).all(axis=1)
    return np.flatnonzero(keep)


def camera_relative(points: SpherePoints | None, rows, offset) -> np.ndarray:
    """float32 [S, 4]: the points ``rows`` as (centre - ``offset``, radius), the origin subtracted in float64."""
    if points is None or not len(rows):
        return no_spheres()
    table = np.empty((len(rows), 4), np.float64)
    table[:, :3] = np.asarray(points.centres, np.float64)[rows] - np.asarray(offset, np.float64)
    table[:, 3] = np.asarray(points.radii, np.float64)[rows]
    return np.ascontiguousarray(table.astype(np.float32))


def camera_relative_steps(points: SpherePoints | None, rows, steps, offset) -> np.ndarray:
    """``Geometry.sphere_motion``: float32 [S, R, 4] of the points ``rows`` at the shutter's time steps ``steps``
    (``motion.Motion.points``, world) as (centre - ``offset``, radius), the origin subtracted in float64; empty
    where they do not move."""
    if points is None or not len(rows) or steps is None:
        return no_sphere_motion()
    table = np.array(np.asarray(steps, np.float64)[:, rows])
    table[..., :3] -= np.asarray(offset, np.float64)
    return np.ascontiguousarray(table.astype(np.float32))


def moving_spheres(sphere_motion: np.ndarray) -> int:
    """How many spheres move over the shutter's time steps ``sphere_motion`` (``Geometry.sphere_motion``)."""
    if sphere_motion.shape[0] < 2:
        return 0
    return int((~(sphere_motion == sphere_motion[:1]).all(axis=(0, 2))).sum())


def point_random(points: SpherePoints | None, rows) -> np.ndarray:
    """float32 [S]: Point Info ▸ Random of the points ``rows`` (0 where the export gave none)."""
    if points is None or points.random is None:
        return np.zeros(len(rows), np.float32)
    return np.ascontiguousarray(np.asarray(points.random, np.float32)[rows])


@inlined
def sphere_at(geometry, s, time):
    """(x, y, z, radius) of sphere ``s`` of ``geometry`` (``Geometry.spheres`` and ``sphere_motion``) at ray time
    ``time`` (0..1 over the shutter): linear between the two time steps around it, as Embree interpolates them;
    the frame's where nothing moves or ``time`` < 0."""
    return row_at(geometry.spheres, geometry.sphere_motion, s, time)


@inlined
def sphere_surface(geometry, s, u, v, time):
    """(point, unit outward normal, the same as shading normal) on sphere ``s`` of ``geometry`` at ray time
    ``time`` where the octahedral code (u, v) points."""
    n = decode(u, v)
    cx, cy, cz, r = sphere_at(geometry, s, time)
    return (cx + r * n[0], cy + r * n[1], cz + r * n[2]), n, n
