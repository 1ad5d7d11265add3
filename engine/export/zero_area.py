"""Geometry that Embree can never hit: a scene whose every triangle has zero area renders as if empty.

Ray tracers skip degenerate triangles (all three corners on one line or one point), so such a scene would
render only the world, or black. ``zero_area_objects`` names the objects when nothing else is left, so the
scene is refused like an empty one.
"""

from __future__ import annotations

import numpy as np

#: Triangles checked at a time: a scene with real geometry usually answers in the first batch.
BATCH = 65536
#: A triangle whose area is below this fraction of its longest edge squared has no width a ray can find
#: (float32 corners hold ~7 digits).
RELATIVE_AREA = 1e-12


def _has_area(corners: np.ndarray) -> np.ndarray:
    """bool [N]: triangles with an area a ray can hit (``corners`` float64 [N, 3, 3])."""
    edge_a = corners[:, 1] - corners[:, 0]
    edge_b = corners[:, 2] - corners[:, 0]
    twice_area = np.linalg.norm(np.cross(edge_a, edge_b), axis=1)
    longest = np.max(np.stack([np.einsum("ij,ij->i", e, e) for e in (edge_a, edge_b, corners[:, 2] - corners[:, 1])]),
                     axis=0)
    return twice_area > RELATIVE_AREA * longest


def zero_area_objects(vertices, triangles, triangle_object, object_names) -> list[tuple[str, int]] | None:
    """[(object name, its triangle count)] when every triangle has zero area, else None (some have area,
    or there are no triangles). ``vertices`` [V, 3], ``triangles`` int [T, 3], ``triangle_object`` int [T]
    into ``object_names`` (None: unnamed)."""
    triangles = np.asarray(triangles)
    if len(triangles) == 0:
        return None
    vertices = np.asarray(vertices, dtype=np.float64)
    for start in range(0, len(triangles), BATCH):
        if _has_area(vertices[triangles[start:start + BATCH]]).any():
            return None
    if triangle_object is None or not object_names:
        return [("(unnamed)", len(triangles))]
    counts = np.bincount(np.asarray(triangle_object), minlength=len(object_names))
    return [(object_names[i], int(counts[i])) for i in np.flatnonzero(counts)]


def zero_area_sentence(objects: list[tuple[str, int]]) -> str:
    """``all 12 triangles of 'Sliver' have zero area`` (the first three objects named)."""
    parts = [f"all {count} triangle{'s' if count != 1 else ''} of '{name}'" for name, count in objects[:3]]
    more = f" and of {len(objects) - 3} more objects" if len(objects) > 3 else ""
    verb = "has" if len(objects) == 1 and objects[0][1] == 1 else "have"
    return ", ".join(parts) + more + f" {verb} zero area (their corners lie on one line or one point)"
