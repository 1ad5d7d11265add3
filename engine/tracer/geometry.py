"""The render's triangles, relative to the render's origin, and the hit-point maths the kernels share.

World positions are float64 (``scene.Scene``); the origin (the camera position, see ``cameras``) is
subtracted in float64 before anything becomes float32, so Embree's float32 precision is spent near the
camera: a scene moved 1e7 m from the origin renders as it does at the origin. Zero-area and non-finite triangles are dropped here
(Embree ids are then this table's rows; ``original`` maps them back for messages).

``Geometry``: ``vertices`` float32 [V, 3] (camera-relative metres), ``triangles`` int32 [T, 3],
``material`` int32 [T], ``normals`` float32 [T, 3, 3] (unit shading normals at the corners) or
[0, 3, 3] for flat shading, ``attributes`` (``SurfaceArrays``: what node materials read, empty arrays
when nothing does), ``flags`` uint8 [T] (``visibility``: the rays that see the triangle's object, and
whether it is a holdout).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from .jit import inlined, kernel

Geometry = namedtuple("Geometry", "vertices triangles material normals attributes flags")

#: UV maps, colour attributes and UV tangents per corner, instance of each triangle, instance rows, the
#: camera position (world = camera-relative + ``offset``) and object-space corner positions; see
#: ``scene.SurfaceAttributes``.
SurfaceArrays = namedtuple("SurfaceArrays", "uvs colors tangents instance objects offset positions")

# Secondary rays start this far (relative to the largest coordinate of the hit point) off the surface:
# ~30 float32 ulps, above Embree's float32 error.
OFFSET_RELATIVE = 4e-6
OFFSET_ABSOLUTE = 1e-7


def prepare_geometry(scene, offset):
    """(``Geometry``, original triangle index [T] int64, dropped count) for ``scene`` with ``offset``
    (the camera position, m) subtracted."""
    vertices = np.asarray(scene.vertices, dtype=np.float64) - np.asarray(offset, dtype=np.float64)
    triangles = np.asarray(scene.triangles, dtype=np.int64).reshape(-1, 3)
    relative32 = vertices.astype(np.float32)
    keep = np.empty(len(triangles), dtype=np.bool_)
    _non_degenerate(relative32, triangles, keep)
    original = np.flatnonzero(keep)
    material = np.asarray(scene.triangle_material, dtype=np.int32)[original]
    normals = np.zeros((0, 3, 3), np.float32)
    if scene.corner_normals is not None and len(scene.corner_normals) == len(triangles):
        normals = np.ascontiguousarray(np.asarray(scene.corner_normals, dtype=np.float32)[original])
    from .visibility import triangle_flags

    geometry = Geometry(np.ascontiguousarray(relative32), np.ascontiguousarray(triangles[original], dtype=np.int32),
                        np.ascontiguousarray(material), normals, surface_arrays(scene.surface, original, offset),
                        triangle_flags(scene, original))
    return geometry, original, int(len(triangles) - len(original))


def surface_arrays(surface, original, offset) -> SurfaceArrays:
    """The kernels' view of ``scene.SurfaceAttributes`` for the kept triangles ``original``, with the camera
    position ``offset`` folded into the world→object transforms."""
    offset = np.asarray(offset, dtype=np.float64)
    if surface is None:
        return SurfaceArrays(np.zeros((0, 0, 3, 2), np.float32), np.zeros((0, 0, 3, 4), np.float32),
                             np.zeros((0, 0, 3, 4), np.float32), np.zeros(0, np.int32), np.zeros((0, 27)), offset,
                             np.zeros((0, 3, 3), np.float32))

    def kept(array, corner_width):
        array = np.asarray(array, dtype=np.float32)
        if array.shape[0] == 0:
            return np.zeros((0, len(original), 3, corner_width), np.float32)
        return np.ascontiguousarray(array[:, original])

    objects = np.array(surface.instances, dtype=np.float64).reshape(-1, 27)
    if len(objects):
        linear = objects[:, :12].reshape(-1, 3, 4)
        linear[:, :, 3] += linear[:, :, :3] @ offset
        objects[:, :12] = linear.reshape(-1, 12)
    instance = np.zeros(0, np.int32)
    if surface.triangle_instance is not None:
        instance = np.ascontiguousarray(np.asarray(surface.triangle_instance, dtype=np.int32)[original])
    positions = np.asarray(surface.positions, dtype=np.float32)
    positions = np.ascontiguousarray(positions[original]) if len(positions) else np.zeros((0, 3, 3), np.float32)
    return SurfaceArrays(kept(surface.uvs, 2), kept(surface.colors, 4), kept(surface.tangents, 4), instance,
                         np.ascontiguousarray(objects), offset, positions)


@kernel
def _non_degenerate(vertices, triangles, keep):
    """``keep[t]``: triangle t has a finite, non-zero area in the float32 vertices Embree will see."""
    for t in range(triangles.shape[0]):
        a, b, c = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        e1x = float(vertices[b, 0]) - float(vertices[a, 0])
        e1y = float(vertices[b, 1]) - float(vertices[a, 1])
        e1z = float(vertices[b, 2]) - float(vertices[a, 2])
        e2x = float(vertices[c, 0]) - float(vertices[a, 0])
        e2y = float(vertices[c, 1]) - float(vertices[a, 1])
        e2z = float(vertices[c, 2]) - float(vertices[a, 2])
        nx = e1y * e2z - e1z * e2y
        ny = e1z * e2x - e1x * e2z
        nz = e1x * e2y - e1y * e2x
        area2 = nx * nx + ny * ny + nz * nz
        keep[t] = math.isfinite(area2) and area2 > 0.0


@inlined
def surface_at(geometry, triangle, u, v):
    """(point, unit geometric normal, unit shading normal on the geometric normal's side) at
    barycentrics (u, v) of ``triangle`` (corner weights 1 - u - v, u, v)."""
    a = geometry.triangles[triangle, 0]
    b = geometry.triangles[triangle, 1]
    c = geometry.triangles[triangle, 2]
    vs = geometry.vertices
    ax, ay, az = float(vs[a, 0]), float(vs[a, 1]), float(vs[a, 2])
    e1 = (float(vs[b, 0]) - ax, float(vs[b, 1]) - ay, float(vs[b, 2]) - az)
    e2 = (float(vs[c, 0]) - ax, float(vs[c, 1]) - ay, float(vs[c, 2]) - az)
    p = (ax + u * e1[0] + v * e2[0], ay + u * e1[1] + v * e2[1], az + u * e1[2] + v * e2[2])
    nx = e1[1] * e2[2] - e1[2] * e2[1]
    ny = e1[2] * e2[0] - e1[0] * e2[2]
    nz = e1[0] * e2[1] - e1[1] * e2[0]
    n = math.sqrt(nx * nx + ny * ny + nz * nz)
    ng = (nx / n, ny / n, nz / n)
    if geometry.normals.shape[0] == 0:
        return p, ng, ng
    w = 1.0 - u - v
    cn = geometry.normals[triangle]
    sx = w * cn[0, 0] + u * cn[1, 0] + v * cn[2, 0]
    sy = w * cn[0, 1] + u * cn[1, 1] + v * cn[2, 1]
    sz = w * cn[0, 2] + u * cn[1, 2] + v * cn[2, 2]
    length = math.sqrt(sx * sx + sy * sy + sz * sz)
    if not (length > 1e-12 and math.isfinite(length)):
        return p, ng, ng
    if sx * ng[0] + sy * ng[1] + sz * ng[2] < 0.0:
        length = -length
    return p, ng, (sx / length, sy / length, sz / length)


@kernel
def offset_origin(p, ng, toward):
    """``p`` moved off its surface along ``ng`` to the side of direction ``toward``."""
    eps = OFFSET_RELATIVE * max(abs(p[0]), abs(p[1]), abs(p[2])) + OFFSET_ABSOLUTE
    if toward[0] * ng[0] + toward[1] * ng[1] + toward[2] * ng[2] < 0.0:
        eps = -eps
    return (p[0] + eps * ng[0], p[1] + eps * ng[1], p[2] + eps * ng[2])
