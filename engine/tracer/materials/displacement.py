"""True displacement: Material ▸ Settings ▸ Displacement "Displacement Only" or "Both" moves a mesh's vertices
by its Material Output's Displacement, as Cycles does before it builds its BVH (``scene/mesh_displace.cpp``).

The material's program runs at each triangle corner (the hit inputs of that corner: its position, normal,
UVs, attributes, object data), and each vertex takes the vector of the first corner that reaches it, as
in Cycles. The vector is in object space, as Cycles reads the output: the Displacement node's
"amount × normal" becomes amount × the object-to-world matrix applied to the object-space normal, so an
object scaled by 2 displaces twice as far. Smooth-shaded displaced triangles get vertex normals averaged
again from their displaced faces (flat ones keep their face normals, which follow the vertices), as
Cycles recomputes them. With motion blur every time step moves by the frame's vector. Everything after
(the Embree scene, emitting triangles' areas) sees the displaced mesh.
"""

from __future__ import annotations

import numpy as np

from ..bsdf.closure import CLOSURE_ROW, MAX_CLOSURES
from ..geometry import FRAME_TIME, surface_at
from ..jit import kernel
from .light_path import FIELDS
from .surface import run_material


def displaces(scene) -> bool:
    """Whether some material of ``scene`` moves its vertices."""
    return any(m.shader is not None and m.shader.displacement >= 0 for m in scene.materials)


@kernel
def corner_displacements(geometry, materials, registers, rows, regs, out):
    """``out[t, k]``: the displacement vector the program of triangle ``t``'s material computes at its
    corner ``k`` (its register ``registers[material]``; rows of other materials are left alone)."""
    for t in range(geometry.triangles.shape[0]):
        material = geometry.material[t]
        r = registers[material]
        if r < 0:
            continue
        for k in range(3):
            u = 1.0 if k == 1 else 0.0
            v = 1.0 if k == 2 else 0.0
            p, ng, ns = surface_at(geometry, t, u, v, FRAME_TIME)
            run_material(materials, geometry, material, t, u, v, p, ng, ns, ns, False, rows, regs, None)
            out[t, k, 0] = regs[r]
            out[t, k, 1] = regs[r + 1]
            out[t, k, 2] = regs[r + 2]


def _to_world(geometry, vectors):
    """Object-space displacements (as the program computed them from world-space normals) → world: each
    vector ``a n`` becomes ``a M m`` with M the object-to-world matrix and m the unit object-space normal
    (∝ Mᵀ n). Triangles without an object row (no object data exported) keep their vectors."""
    instance = geometry.attributes.instance
    objects = geometry.attributes.objects
    if len(instance) == 0 or len(objects) == 0:
        return vectors
    rows = instance[:len(vectors)]
    world_to_object = objects[:, :12].reshape(-1, 3, 4)[:, :, :3]
    to_world = np.linalg.pinv(world_to_object)[np.maximum(rows, 0)]  # [T, 3, 3] (a zero scale: no move)
    length = np.linalg.norm(vectors, axis=2, keepdims=True)
    direction = np.divide(vectors, length, out=np.zeros_like(vectors), where=length > 0)
    in_object = np.einsum("tji,tkj->tki", to_world, direction)  # Mᵀ n per corner
    in_object /= np.maximum(np.linalg.norm(in_object, axis=2, keepdims=True), 1e-30)
    moved = np.einsum("tij,tkj->tki", to_world, in_object) * length
    return np.where((rows >= 0)[:, None, None], moved, vectors)


def _recomputed_normals(vertices, triangles, normals, displaced, flat):
    """Corner normals after the move: smooth displaced triangles take their vertices' normals, the sum of the
    unit normals of the displaced triangles around them (Cycles' ``add_vertex_normals``), flat ones (``flat``
    bool [T], or None: those whose three corner normals agreed) their new face normal."""
    corners = vertices[triangles[displaced]].astype(np.float64)
    faces = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    unit_faces = faces / np.maximum(np.linalg.norm(faces, axis=1, keepdims=True), 1e-30)
    summed = np.zeros((len(vertices), 3))
    for k in range(3):
        np.add.at(summed, triangles[displaced, k], unit_faces)
    smooth_vertex = summed / np.maximum(np.linalg.norm(summed, axis=1, keepdims=True), 1e-30)
    if flat is None:
        old = normals[displaced]
        flat_here = np.all(np.abs(old - old[:, :1]).max(axis=2) < 1e-6, axis=1)
    else:
        flat_here = np.asarray(flat, bool)[displaced]
    new = smooth_vertex[triangles[displaced]]
    new[flat_here] = unit_faces[flat_here, None, :]
    out = normals.copy()
    out[displaced] = new.astype(np.float32)
    return out


def displace(geometry, material_table, flat=None):
    """``geometry`` (``geometry.Geometry``) with the vertices of displacing materials moved (and their
    normals and motion steps with them); the same object when no triangle displaces. ``flat`` bool [T]:
    the triangles shaded flat (``scene.Scene.triangle_flat`` of the kept rows), or None."""
    registers = material_table.displacement
    triangles = geometry.triangles
    if len(registers) == 0 or len(triangles) == 0:
        return geometry
    displaced = registers[geometry.material[:len(triangles)]] >= 0
    if not displaced.any():
        return geometry
    vectors = np.zeros((len(triangles), 3, 3))
    regs = np.zeros(max(int(material_table.register_count), 1) + FIELDS)
    corner_displacements(geometry, material_table.arrays, registers, np.zeros((MAX_CLOSURES, CLOSURE_ROW)), regs,
                         vectors)
    vectors = _to_world(geometry, vectors)
    vectors[~np.isfinite(vectors)] = 0.0
    # Each vertex moves by its first displaced corner's vector (Cycles' order: triangle by triangle).
    corner_vertex = triangles[displaced].ravel()
    vertex, first = np.unique(corner_vertex, return_index=True)
    offset = np.zeros((len(geometry.vertices), 3))
    offset[vertex] = vectors[displaced].reshape(-1, 3)[first]
    vertices = (geometry.vertices.astype(np.float64) + offset).astype(np.float32)
    normals = geometry.normals
    if len(normals):
        normals = _recomputed_normals(vertices, triangles, normals, displaced, flat)
    motion = geometry.motion
    if len(motion):
        motion = (motion + offset[None].astype(np.float32)).astype(np.float32)
    return geometry._replace(vertices=np.ascontiguousarray(vertices), normals=np.ascontiguousarray(normals),
                             motion=np.ascontiguousarray(motion))
