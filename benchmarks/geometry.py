"""Triangle builders for the benchmark scenes: quads, boxes, spheres, prisms.

Every builder returns ``(vertices float32 [V, 3] in metres, triangles int32 [T, 3],
corner_normals float32 [T, 3, 3] or None)``; :class:`MeshBuilder` concatenates
parts and tags each part with a material and an object name.
"""

from __future__ import annotations

import numpy as np


def quad(p0, p1, p2, p3):
    """Two triangles of the planar quad p0 p1 p2 p3 (counter-clockwise seen from its front)."""
    vertices = np.array([p0, p1, p2, p3], dtype=np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)
    return vertices, triangles, None


def box(centre, size, rotation_z_rad=0.0):
    """A closed cuboid of full extents ``size`` (m), rotated about Z, outward faces."""
    sx, sy, sz = (np.asarray(size, dtype=np.float64) / 2.0)
    corners = np.array(
        [[x, y, z] for z in (-sz, sz) for y in (-sy, sy) for x in (-sx, sx)], dtype=np.float64
    )
    c, s = np.cos(rotation_z_rad), np.sin(rotation_z_rad)
    rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    corners = corners @ rotation.T + np.asarray(centre, dtype=np.float64)
    # corner index = x + 2 y + 4 z (0 = min, 1 = max along each axis)
    faces = [
        (0, 2, 3, 1),  # bottom (-z)
        (4, 5, 7, 6),  # top (+z)
        (0, 1, 5, 4),  # -y
        (2, 6, 7, 3),  # +y
        (0, 4, 6, 2),  # -x
        (1, 3, 7, 5),  # +x
    ]
    triangles = []
    for a, b, c_, d in faces:
        triangles += [[a, b, c_], [a, c_, d]]
    return corners.astype(np.float32), np.array(triangles, dtype=np.int32), None


def icosphere(centre, radius_m, subdivisions):
    """A sphere of 20 * 4**subdivisions triangles with smooth (radial) corner normals."""
    t = (1.0 + 5.0 ** 0.5) / 2.0
    vertices = np.array(
        [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]],
        dtype=np.float64,
    )
    triangles = np.array(
        [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]],
        dtype=np.int64,
    )
    vertices /= np.linalg.norm(vertices, axis=1, keepdims=True)
    for _ in range(subdivisions):
        edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
        edges.sort(axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        midpoints = vertices[unique[:, 0]] + vertices[unique[:, 1]]
        midpoints /= np.linalg.norm(midpoints, axis=1, keepdims=True)
        mid = inverse.reshape(3, -1) + len(vertices)
        m01, m12, m20 = mid
        a, b, c = triangles.T
        triangles = np.concatenate(
            [np.stack(x, axis=1) for x in ((a, m01, m20), (b, m12, m01), (c, m20, m12), (m01, m12, m20))]
        )
        vertices = np.concatenate([vertices, midpoints])
    normals = vertices[triangles].astype(np.float32)
    positions = (vertices * radius_m + np.asarray(centre, dtype=np.float64)).astype(np.float32)
    return positions, triangles.astype(np.int32), normals


def displaced_sphere(centre, radius_m, rings, segments, amplitude=0.06, frequency=9):
    """A latitude-longitude sphere of ~2 * rings * segments flat triangles with a
    bumpy radial displacement (relative ``amplitude``); the scale test mesh."""
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    th, ph = np.meshgrid(theta, phi, indexing="ij")
    r = radius_m * (1.0 + amplitude * np.sin(frequency * th) * np.sin(frequency * ph)
                    + 0.5 * amplitude * np.sin(3 * frequency * th + 2 * ph))
    points = np.stack([r * np.sin(th) * np.cos(ph), r * np.sin(th) * np.sin(ph), r * np.cos(th)], axis=-1)
    vertices = (points.reshape(-1, 3) + np.asarray(centre)).astype(np.float32)
    index = np.arange((rings + 1) * segments).reshape(rings + 1, segments)
    nxt = np.roll(index, -1, axis=1)
    a, b, c, d = index[:-1], nxt[:-1], nxt[1:], index[1:]
    # the first and last rings collapse to a point: keep one triangle of each quad there
    upper = np.stack([a, d, c], axis=-1)[1:].reshape(-1, 3)
    lower = np.stack([a, c, b], axis=-1)[:-1].reshape(-1, 3)
    triangles = np.concatenate([upper, lower]).astype(np.int32)
    return vertices, triangles, None


def triangular_prism(centre, side_m, height_m, rotation_z_rad=0.0):
    """An equilateral (60 degree) prism standing on Z: a triangle of ``side_m`` in
    XY extruded over ``height_m``, closed, outward faces, flat shading."""
    angles = rotation_z_rad + np.array([90.0, 210.0, 330.0]) * np.pi / 180.0
    circumradius = side_m / np.sqrt(3.0)
    xy = np.stack([np.cos(angles), np.sin(angles)], axis=1) * circumradius
    cx, cy, cz = centre
    bottom = np.column_stack([xy[:, 0] + cx, xy[:, 1] + cy, np.full(3, cz - height_m / 2)])
    top = bottom + np.array([0.0, 0.0, height_m])
    vertices = np.concatenate([bottom, top]).astype(np.float32)
    triangles = [[0, 2, 1], [3, 4, 5]]
    for i in range(3):
        j = (i + 1) % 3
        triangles += [[i, j, j + 3], [i, j + 3, i + 3]]
    return vertices, np.array(triangles, dtype=np.int32), None


class MeshBuilder:
    """Collects parts into one triangle soup with material and object indices."""

    def __init__(self):
        self._vertices, self._triangles, self._normals = [], [], []
        self._material, self._object = [], []
        self.object_names: list[str] = []
        self._count = 0

    def add(self, name, material_index, part):
        """Append ``part`` = (vertices, triangles, corner_normals or None)."""
        vertices, triangles, normals = part
        if normals is None:
            corners = vertices[triangles].astype(np.float64)
            n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
            normals = np.repeat(n[:, None, :], 3, axis=1)
        self._vertices.append(vertices)
        self._triangles.append(triangles + self._count)
        self._normals.append(normals.astype(np.float32))
        self._material.append(np.full(len(triangles), material_index, dtype=np.int32))
        self._object.append(np.full(len(triangles), len(self.object_names), dtype=np.int32))
        self.object_names.append(name)
        self._count += len(vertices)

    def arrays(self, smooth=True):
        """(vertices, triangles, triangle_material, triangle_object, corner_normals)."""
        normals = np.concatenate(self._normals) if smooth else None
        return (
            np.concatenate(self._vertices).astype(np.float32),
            np.concatenate(self._triangles).astype(np.int32),
            np.concatenate(self._material),
            np.concatenate(self._object),
            normals,
        )
