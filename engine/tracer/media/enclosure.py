"""Which media enclose a point (the camera): a ray from it crosses a closed mesh's surface an odd number of
times when it starts inside. The ray goes in a fixed, irrational-looking direction so that it does not graze
the edges of axis-aligned meshes; triangles are tested in numpy (Möller-Trumbore), once per render."""

from __future__ import annotations

import numpy as np

_DIRECTION = np.array([0.5773, 0.5681, 0.5866]) / np.linalg.norm([0.5773, 0.5681, 0.5866])


def crossings(origin, vertices, triangles) -> int:
    """How many of ``triangles`` (indices into ``vertices`` [V, 3], metres) a ray from ``origin`` crosses."""
    if len(triangles) == 0:
        return 0
    v = np.asarray(vertices, dtype=np.float64)
    a, b, c = v[triangles[:, 0]], v[triangles[:, 1]], v[triangles[:, 2]]
    e1, e2 = b - a, c - a
    p = np.cross(_DIRECTION, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = np.asarray(origin, dtype=np.float64) - a
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, e1)
    w = (q @ _DIRECTION) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    return int(np.count_nonzero(ok & (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 0)))


def enclosing_media(point, vertices, triangles, triangle_material, materials) -> list[int]:
    """Indices of the ``materials`` (``scene.Material``) with a medium whose triangles enclose ``point``
    (world, m)."""
    found = []
    material_of = np.asarray(triangle_material)
    for index, material in enumerate(materials):
        if getattr(material, "medium", None) is None:
            continue
        if crossings(point, vertices, np.asarray(triangles)[material_of == index]) % 2 == 1:
            found.append(index)
    return found
