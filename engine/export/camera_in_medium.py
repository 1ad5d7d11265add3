"""Whether the camera stands inside a closed mesh that holds a medium: Prism's camera rays start outside
every medium (``tracer/media``), so such a view renders without the medium around the camera, and the
export says so, naming the material.

Inside is decided by parity: a ray from the camera crosses a closed mesh's surface an odd number of times
when it starts inside. The ray goes in a fixed, irrational-looking direction so that it does not graze
the edges of axis-aligned meshes; triangles are tested in numpy (Möller-Trumbore), once per export.
"""

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


def camera_in_medium_warnings(tracer_scene) -> list[str]:
    """One warning per material with a medium whose mesh encloses the camera."""
    origin = tracer_scene.camera.camera_to_world[:3, 3]
    found = []
    material_of = np.asarray(tracer_scene.triangle_material)
    for index, material in enumerate(tracer_scene.materials):
        if getattr(material, "medium", None) is None:
            continue
        triangles = np.asarray(tracer_scene.triangles)[material_of == index]
        if crossings(origin, tracer_scene.vertices, triangles) % 2 == 1:
            found.append(f"Material '{material.name}': the camera is inside the volume it fills; Prism starts camera "
                         "rays outside every medium, so the view renders without this volume until a ray enters it. "
                         "Move the camera out of the mesh.")
    return found
