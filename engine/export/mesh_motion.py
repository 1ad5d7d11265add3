"""Meshes through the shutter: their vertices and corner normals at each time step (``tracer.motion.Motion``),
and where they are one frame before and after for the Vector pass.

``export.motion`` re-exports the scene at each step; each mesh's vertices there are matched to the frame's by
object (instances of one piece of geometry together, pieces of one name by occurrence) and then by vertex order,
as Cycles matches a mesh's vertices (``sync_mesh_motion``), through ``motion_steps.object_steps``, so one mesh that
changes its number of vertices during the shutter no longer stops the others from moving.

A mesh whose vertices carry a ``velocity`` attribute moves by it instead, at every step, each vertex in a straight
line carried by the object's own transform motion (``velocity``), as Cycles takes that attribute over the steps
for any mesh that has one (a liquid simulation's surface, an Alembic cache, Geometry Nodes). Its corner normals
stay the frame's, as in Cycles. A mesh that changes its number of vertices without one stays still where it is at
the frame, named in a warning; Cycles drops its motion too, without a word.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from .motion_steps import StepRows, matched_steps, object_steps
from .velocity import Transforms, moved_positions, velocity_offsets


@dataclass(frozen=True)
class MeshWarnings:
    """The warnings for a mesh whose number of vertices changes and that has no velocity (``changing(name)``), and
    for one moving with Object ▸ Motion Blur ▸ Deformation off (``deforming(name)``)."""

    changing: Callable[[str], str]
    deforming: Callable[[str], str]


def _vertices(geometry) -> np.ndarray:
    return np.asarray(geometry.vertices, np.float64)


def _vertex_owner(geometry) -> np.ndarray:
    return np.asarray(geometry.vertex_object, np.int64)


def _normals(geometry) -> np.ndarray:
    return np.asarray(geometry.corner_normals, np.float64).reshape(-1, 9)


def _triangle_owner(geometry) -> np.ndarray:
    return np.asarray(geometry.triangle_object, np.int64)


def mesh_steps(frame, steps, settings, count, warnings, seconds, said: MeshWarnings, with_normals: bool = True):
    """(vertices float64 [S, V, 3] or None where no vertex moves, corner normals float32 [S, T, 3, 3] or None) of
    the meshes of ``frame`` (``meshes.ExportedGeometry`` at the frame) at the ``count`` time steps ``seconds`` [S]
    from the frame, from ``steps`` ((``ExportedGeometry``, its object names) exported at each), per object as the
    module says; the normals only ``with_normals`` (the Vector pass needs none). ``settings``: object name →
    (motion blur on, steps, deformation on)."""
    names = list(frame.object_names)
    if not len(frame.vertices):
        return None, None
    drift = velocity_offsets(frame.vertex_velocity, seconds)
    moves_by_velocity = moved_positions(frame.vertices, drift, frame.vertex_object, step_transforms(frame, steps))
    vertex_rows = StepRows(_vertices(frame), _vertex_owner(frame), matched_steps(names, steps, _vertices,
                                                                                _vertex_owner, 3),
                           said.changing, said.deforming, moves_by_velocity, has_radius=False)
    vertices = object_steps(vertex_rows, names, settings, count, warnings)
    if vertices is None or not with_normals or frame.corner_normals is None or not len(frame.corner_normals):
        return vertices, None
    normal_rows = StepRows(_normals(frame), _triangle_owner(frame), matched_steps(names, steps, _normals,
                                                                               _triangle_owner, 9),
                           said.changing, said.deforming, _frame_normals_where_velocity(frame, count),
                           has_radius=False)
    normals = object_steps(normal_rows, names, settings, count, [])  # what it could say, the vertices said
    return vertices, None if normals is None else normals.reshape(count, -1, 3, 3).astype(np.float32)


def step_transforms(frame, steps) -> Transforms:
    """``velocity.Transforms`` of the objects of ``frame`` (``meshes.ExportedGeometry``) and of ``steps``
    ((``ExportedGeometry``, its object names) exported at each time step)."""
    return Transforms(list(frame.object_names), list(frame.object_matrices),
                      [(list(geometry.object_matrices), names) for geometry, names in steps])


def _frame_normals_where_velocity(frame, count) -> np.ndarray | None:
    """float64 [S, T, 9]: the frame's corner normals at every step for the triangles of meshes moved by their
    velocity, NaN for the others; None without velocities."""
    if frame.vertex_velocity is None:
        return None
    has = np.isfinite(frame.vertex_velocity).all(axis=1)
    carried = np.bincount(_vertex_owner(frame)[has], minlength=len(frame.object_names)) > 0
    rows = np.where(carried[_triangle_owner(frame)][:, None], _normals(frame), np.nan)
    return np.repeat(rows[None], count, axis=0)


def changing_mesh_warning(name: str) -> str:
    """The motion blur warning for a mesh whose number of vertices changes during the shutter, without velocity."""
    return (f"Object '{name}': its number of vertices changes during the shutter (geometry added or removed over "
            "time) and it has no 'velocity' attribute, so Prism cannot follow its vertices: it is rendered still "
            "where it is at the frame, without motion blur (as Cycles renders it).")


def deforming_mesh_warning(name: str) -> str:
    return (f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs the mesh's vertices as they move, so "
            "any deformation (armature, shape keys, modifiers) is blurred too (Cycles blurs only the object's "
            "transform).")
