"""The baked object's loop triangles in world space, as Blender numbers them for a bake.

Blender's bake pixels name a loop triangle of the object's evaluated mesh (modifiers applied: the mesh
``BKE_mesh_new_from_object`` gives, whose triangles are ``Mesh.loop_triangles``), so the triangles are
read from ``Object.to_mesh()`` of the evaluated object, in that order, with ``foreach_get``.
"""

from __future__ import annotations

import numpy as np

from .bake_points import BakeTriangles


def _read(collection, attribute: str, count: int, width: int, dtype) -> np.ndarray:
    values = np.empty(count * width, dtype)
    collection.foreach_get(attribute, values)
    return values.reshape(count, width) if width > 1 else values


def bake_triangles(evaluated_object) -> BakeTriangles:
    """World-space corners and corner normals of ``evaluated_object``'s loop triangles."""
    mesh = evaluated_object.to_mesh()
    try:
        mesh.calc_loop_triangles()
        tris = mesh.loop_triangles
        count = len(tris)
        co = _read(mesh.vertices, "co", len(mesh.vertices), 3, np.float32).astype(np.float64)
        tri_vertices = _read(tris, "vertices", count, 3, np.int32)
        tri_loops = _read(tris, "loops", count, 3, np.int32)
        # Corner normals: smooth, flat, sharp edges and custom normals as Cycles reads them (Blender 4.1+).
        normals = _read(mesh.corner_normals, "vector", len(mesh.corner_normals), 3, np.float32).astype(np.float64)
    finally:
        evaluated_object.to_mesh_clear()
    matrix = np.array(evaluated_object.matrix_world, np.float64)
    linear, translation = matrix[:3, :3], matrix[:3, 3]
    corners = co[tri_vertices] @ linear.T + translation
    # Normals transform by the inverse transpose; a mirroring transform also turns the triangles' winding
    # round, which ``bake_points`` reads the face normal from.
    corner_normals = normals[tri_loops] @ np.linalg.inv(linear)
    corner_normals /= np.maximum(np.linalg.norm(corner_normals, axis=-1, keepdims=True), 1e-30)
    return BakeTriangles(corners, corner_normals, bool(np.linalg.det(linear) < 0.0))
