"""One evaluated mesh in object space, read with ``foreach_get`` (no Python loop over its elements)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class LocalMesh:
    """Triangles of one evaluated mesh in object space.

    ``vertices`` float64 [V, 3] (exact copies of Blender's float32 coordinates),
    ``triangles`` int32 [T, 3], ``slot_index`` int32 [T] (material slot of each
    triangle), ``corner_normals`` float32 [T, 3, 3], ``slot_materials`` the
    object's material per slot (None for an empty slot).
    """

    vertices: np.ndarray
    triangles: np.ndarray
    slot_index: np.ndarray
    corner_normals: np.ndarray
    slot_materials: list


def read_mesh(obj) -> LocalMesh | None:
    """The evaluated mesh of ``obj`` (modifiers applied); None when it has no triangles."""
    mesh = obj.to_mesh()
    if mesh is None:
        return None
    try:
        mesh.calc_loop_triangles()
        vertex_count, triangle_count = len(mesh.vertices), len(mesh.loop_triangles)
        if triangle_count == 0:
            return None
        vertices = np.empty(vertex_count * 3, np.float32)
        mesh.vertices.foreach_get("co", vertices)
        triangles = np.empty(triangle_count * 3, np.int32)
        mesh.loop_triangles.foreach_get("vertices", triangles)
        slot_index = np.empty(triangle_count, np.int32)
        mesh.loop_triangles.foreach_get("material_index", slot_index)
        loops = np.empty(triangle_count * 3, np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        normals = np.empty(len(mesh.loops) * 3, np.float32)
        mesh.corner_normals.foreach_get("vector", normals)
        return LocalMesh(
            vertices=vertices.reshape(-1, 3).astype(np.float64),
            triangles=triangles.reshape(-1, 3),
            slot_index=slot_index,
            corner_normals=normals.reshape(-1, 3)[loops].reshape(-1, 3, 3),
            slot_materials=[slot.material for slot in obj.material_slots],
        )
    finally:
        obj.to_mesh_clear()
