"""One evaluated mesh in object space, read with ``foreach_get`` (no Python loop over its elements), with
the per-corner data its materials read (``mesh_attributes``) when asked for."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .mesh_attributes import corner_attribute, corner_tangents, corner_uvs
from .velocity import read_velocity


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
    uvs: dict = field(default_factory=dict)  # UV slot → float32 [T, 3, 2]
    attributes: dict = field(default_factory=dict)  # attribute slot → float32 [T, 3, 4]
    tangents: dict = field(default_factory=dict)  # tangent slot → float32 [T, 3, 4] (object space + sign)
    texture_space: tuple = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))  # (location, size) for generated coordinates
    flat: np.ndarray | None = None  # bool [T]: the triangle's face is shaded flat (what displacement recomputes)
    velocity: np.ndarray | None = None  # float64 [V, 3]: the vertices' ``velocity`` attribute (m/s), or None


@dataclass
class AttributeRequest:
    """Per-corner data to read: slot → name, for UV maps, attributes and tangents."""

    uvs: dict = field(default_factory=dict)
    attributes: dict = field(default_factory=dict)
    tangents: dict = field(default_factory=dict)


def read_mesh(obj, request: AttributeRequest | None = None, warn=None) -> LocalMesh | None:
    """The evaluated mesh of ``obj`` (modifiers applied) and the data ``request`` names; None when it has no
    triangles. ``warn(message)`` reports what could not be read as Blender does."""
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
        loops = np.empty(triangle_count * 3, np.int32)
        mesh.loop_triangles.foreach_get("loops", loops)
        polygon = np.empty(triangle_count, np.int32)
        mesh.loop_triangle_polygons.foreach_get("value", polygon)
        normals = np.empty(len(mesh.loops) * 3, np.float32)
        mesh.corner_normals.foreach_get("vector", normals)
        slot_index = _per_triangle(mesh, "material_index", "INT", polygon, 0).astype(np.int32)
        local = LocalMesh(
            vertices=vertices.reshape(-1, 3).astype(np.float64),
            triangles=_corner_vertices(mesh, loops).reshape(-1, 3),
            slot_index=slot_index,
            corner_normals=normals.reshape(-1, 3)[loops].reshape(-1, 3, 3),
            slot_materials=[slot.material for slot in obj.material_slots],
            flat=_per_triangle(mesh, "sharp_face", "BOOLEAN", polygon, False),
            velocity=read_velocity(mesh, vertex_count),
        )
        if request is not None:
            _read_attributes(obj, mesh, local, loops, request, warn)
        return local
    finally:
        obj.to_mesh_clear()


def _corner_vertices(mesh, loops: np.ndarray) -> np.ndarray:
    """The vertex of each of ``loops`` (corners), int32. Read from the corner attribute Blender keeps them in:
    a hundred times faster than ``loop_triangles``' "vertices" or ``loops``' "vertex_index", which go through
    Python's per-element access (0.15 s against 0.001 s for a million triangles)."""
    corner_vert = mesh.attributes.get(".corner_vert")
    if corner_vert is None or corner_vert.domain != "CORNER":  # not in Blender's layout: ask per triangle
        vertices = np.empty(len(loops), np.int32)
        mesh.loop_triangles.foreach_get("vertices", vertices)
        return vertices
    values = np.empty(len(mesh.loops), np.int32)
    corner_vert.data.foreach_get("value", values)
    return values[loops]


def _per_triangle(mesh, name: str, data_type: str, polygon: np.ndarray, default) -> np.ndarray:
    """A face attribute (``material_index``, ``sharp_face``) at each triangle's face ``polygon``; ``default``
    everywhere when the mesh has none (Blender stores them only once a face differs)."""
    attribute = mesh.attributes.get(name)
    if attribute is None or attribute.domain != "FACE" or attribute.data_type != data_type:
        return np.full(len(polygon), default)
    values = np.empty(len(mesh.polygons), np.int32 if data_type == "INT" else bool)
    attribute.data.foreach_get("value", values)
    return values[polygon]


def _read_attributes(obj, mesh, local, loops, request, warn):
    for slot, name in request.uvs.items():
        uv = corner_uvs(mesh, name, loops)
        if uv is not None:
            local.uvs[slot] = uv
    for slot, name in request.attributes.items():
        values = corner_attribute(mesh, name, loops, local.triangles)
        if values is not None:
            local.attributes[slot] = values
    for slot, name in request.tangents.items():
        uv = corner_uvs(mesh, name, loops)
        if uv is None:
            continue

        def report(name=name):
            if warn is not None:
                warn(f"Object '{obj.original.name}': Blender computes UV tangents for triangles and quads only; "
                     f"Prism uses flat tangents per triangle for UV map '{name or 'active'}' (triangulate the "
                     "mesh for exact normal maps).")

        local.tangents[slot] = corner_tangents(mesh, name, loops, local.vertices, local.triangles, uv,
                                               local.corner_normals, report)
    data = obj.data
    if hasattr(data, "texspace_location"):
        local.texture_space = (tuple(data.texspace_location), tuple(data.texspace_size))
