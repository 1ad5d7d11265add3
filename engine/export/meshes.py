"""Evaluated mesh instances → one world-space triangle soup, read with ``foreach_get``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..tracer.scene import Material
from .materials import DEFAULT_MATERIAL, export_material

_GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT", "CURVES"}


@dataclass
class ExportedGeometry:
    vertices: np.ndarray
    triangles: np.ndarray
    triangle_material: np.ndarray
    triangle_object: np.ndarray
    corner_normals: np.ndarray
    object_names: list[str]
    materials: list[Material]


@dataclass
class _LocalMesh:
    """One evaluated mesh in object space."""

    vertices: np.ndarray  # float64 [V, 3]
    triangles: np.ndarray  # int32 [T, 3]
    slot_index: np.ndarray  # int32 [T]
    corner_normals: np.ndarray  # float64 [T, 3, 3]
    slot_materials: list


def _read_mesh(obj) -> _LocalMesh | None:
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
        return _LocalMesh(
            vertices=vertices.reshape(-1, 3).astype(np.float64),
            triangles=triangles.reshape(-1, 3),
            slot_index=slot_index,
            corner_normals=normals.reshape(-1, 3)[loops].reshape(-1, 3, 3).astype(np.float64),
            slot_materials=[slot.material for slot in obj.material_slots],
        )
    finally:
        obj.to_mesh_clear()


def _normalise(vectors: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return vectors / np.where(length > 0, length, 1.0)


def export_meshes(depsgraph, warnings: list[str] | None = None) -> ExportedGeometry:
    """Every visible geometry instance, transformed to world space (metres); material warnings
    (inputs Prism does not model) are appended to ``warnings``."""
    local_meshes: dict[tuple, _LocalMesh | None] = {}
    material_index: dict[str, int] = {}
    materials: list[Material] = []
    parts = []
    object_names: list[str] = []

    def global_material(material) -> int:
        key = material.name if material is not None else None
        if key not in material_index:
            material_index[key] = len(materials)
            materials.append(export_material(material, warnings) if material is not None else DEFAULT_MATERIAL)
        return material_index[key]

    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type not in _GEOMETRY_TYPES:
            continue
        key = (obj.original.name, obj.data.as_pointer() if obj.data is not None else 0)
        if key not in local_meshes:
            local_meshes[key] = _read_mesh(obj)
        local = local_meshes[key]
        if local is None:
            continue
        matrix = np.array(instance.matrix_world, dtype=np.float64)
        world_vertices = local.vertices @ matrix[:3, :3].T + matrix[:3, 3]
        normal_matrix = np.linalg.inv(matrix[:3, :3]).T if abs(np.linalg.det(matrix[:3, :3])) > 0 else matrix[:3, :3]
        world_normals = _normalise(local.corner_normals @ normal_matrix.T)
        slots = [global_material(m) for m in local.slot_materials] or [global_material(None)]
        slot_lookup = np.asarray(slots, dtype=np.int32)
        triangle_material = slot_lookup[np.clip(local.slot_index, 0, len(slots) - 1)]
        parts.append((world_vertices, local.triangles, triangle_material, world_normals, len(object_names)))
        object_names.append(obj.name)

    if not parts:
        return ExportedGeometry(
            vertices=np.zeros((0, 3), np.float32),
            triangles=np.zeros((0, 3), np.int32),
            triangle_material=np.zeros(0, np.int32),
            triangle_object=np.zeros(0, np.int32),
            corner_normals=np.zeros((0, 3, 3), np.float32),
            object_names=[],
            materials=materials or [DEFAULT_MATERIAL],
        )
    offsets = np.cumsum([0] + [len(p[0]) for p in parts[:-1]])
    return ExportedGeometry(
        vertices=np.concatenate([p[0] for p in parts]).astype(np.float32),
        triangles=np.concatenate([p[1] + offset for p, offset in zip(parts, offsets)]).astype(np.int32),
        triangle_material=np.concatenate([p[2] for p in parts]),
        triangle_object=np.concatenate([np.full(len(p[1]), p[4], np.int32) for p in parts]),
        corner_normals=np.concatenate([p[3] for p in parts]).astype(np.float32),
        object_names=object_names,
        materials=materials,
    )
