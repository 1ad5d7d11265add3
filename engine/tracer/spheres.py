"""Spheres: the points of Blender's Point Cloud objects, each a sphere of its own radius.

The export fills ``scene.Scene.points`` (a ``SpherePoints``, world space, float64). ``camera_relative``
turns it into the float32 table Embree and the kernels share (``Geometry.spheres`` [S, 4]: centre minus
the render's origin, radius), as the triangles' vertices are. Spheres are rows of the render's
primitives after the triangles: row T + s is sphere s, so ``Geometry.material`` and ``Geometry.flags``
(and the instance of each row, when node materials read object data) hold T + S entries and every
stage reads a sphere's material the way it reads a triangle's. A sphere hit's (u, v) is its outward
normal as an octahedral code (``embree.queries.closest_hit``), so ``surface_at`` rebuilds the point
exactly on the sphere. Spheres do not move with motion blur, carry no UV map and are not sampled as
lights (an emissive sphere is found by rays, as Cycles finds emissive points).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .jit import inlined
from .octahedral import decode


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


def point_random(points: SpherePoints | None, rows) -> np.ndarray:
    """float32 [S]: Point Info ▸ Random of the points ``rows`` (0 where the export gave none)."""
    if points is None or points.random is None:
        return np.zeros(len(rows), np.float32)
    return np.ascontiguousarray(np.asarray(points.random, np.float32)[rows])


@inlined
def sphere_surface(spheres, s, u, v):
    """(point, unit outward normal, the same as shading normal) on sphere ``s`` of ``spheres`` where the
    octahedral code (u, v) points."""
    n = decode(u, v)
    cx, cy, cz, r = float(spheres[s, 0]), float(spheres[s, 1]), float(spheres[s, 2]), float(spheres[s, 3])
    return (cx + r * n[0], cy + r * n[1], cz + r * n[2]), n, n
