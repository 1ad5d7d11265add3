"""Ray visibility of objects: each kind of ray is traced against the triangles it can see.

embreex has no per-ray filters, so a scene where some object hides from some rays gets one Embree
scene per distinct set of visible triangles (most scenes: one or two), with the render's triangle id
of each of its triangles. A queue's rays are grouped by kind — camera rays at the first bounce, then
by what the path's last scattering was (``state.LAST_DIFFUSE``, ``LAST_TRANSMISSION``, else glossy) —
and each group is traced against its scene. Shadow rays see the shadow-visible triangles.
"""

from __future__ import annotations

import numpy as np

from .accel import Accel
from .geometry import Geometry
from .state import LAST_DIFFUSE, LAST_TRANSMISSION
from .visibility import ALL_RAYS, RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_SHADOW, RAY_TRANSMISSION

_CLASSES = (RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_TRANSMISSION, RAY_SHADOW)


def needs_ray_classes(geometry) -> bool:
    """True when some triangle hides from some kind of ray."""
    return bool(len(geometry.flags)) and bool(((geometry.flags & ALL_RAYS) != ALL_RAYS).any())


class _Subset:
    """The rows ``chosen`` (triangles, then spheres) as a geometry of their own; ``ids`` its rows' render rows."""

    def __init__(self, geometry, chosen):
        self.ids = np.flatnonzero(chosen).astype(np.int32)
        count = len(geometry.triangles)
        triangles, spheres = self.ids[self.ids < count], self.ids[self.ids >= count] - count
        sub = Geometry(geometry.vertices, np.ascontiguousarray(geometry.triangles[triangles]),
                       geometry.material[self.ids], geometry.normals[:0], geometry.attributes,
                       geometry.flags[self.ids], geometry.motion,
                       geometry.motion_normals[:, triangles] if len(geometry.motion_normals) else geometry.motion_normals,
                       np.ascontiguousarray(geometry.spheres[spheres]), geometry.sphere_random[spheres])
        self.accel = Accel(sub)

    def _map(self, hit):
        triangle, t, u, v = hit
        if not len(self.ids):  # nothing this kind of ray sees (every object hidden from it): all rays miss
            return np.full(len(triangle), -1, np.int32), t, u, v
        mapped = np.where(triangle >= 0, self.ids[np.maximum(triangle, 0)], -1).astype(np.int32)
        return mapped, t, u, v


class RayClassAccel:
    """``Accel``'s queries with ray visibility (``trace`` uses it instead of ``Accel`` when
    ``needs_ray_classes``)."""

    def __init__(self, geometry, full: Accel):
        self._full = full
        self._scenes = {}
        self._of_class = {}
        for ray in _CLASSES:
            chosen = (geometry.flags & ray) != 0
            if chosen.all():
                self._of_class[ray] = None
                continue
            key = chosen.tobytes()
            if key not in self._scenes:
                self._scenes[key] = _Subset(geometry, chosen)
            self._of_class[ray] = self._scenes[key]

    def _query(self, ray, rays, count, kind):
        subset = self._of_class[ray]
        accel = self._full if subset is None else subset.accel
        if kind == "occluded":
            return accel.occluded(rays, count)
        hit = accel.intersect(rays, count) if kind == "closest" else accel.intersect_before(rays, count)
        return hit if subset is None else subset._map(hit)

    def intersect(self, rays, count, state, depth):
        """Closest hits of the first ``count`` rays, each against what its kind of ray sees."""
        if depth == 0:
            return self._query(RAY_CAMERA, rays, count, "closest")
        flags = state.flags[rays.path[:count]]
        kinds = np.where(flags & LAST_TRANSMISSION, RAY_TRANSMISSION, np.where(flags & LAST_DIFFUSE, RAY_DIFFUSE,
                                                                                 RAY_GLOSSY))
        triangle = np.empty(count, np.int32)
        t, u, v = (np.empty(count, np.float32) for _ in range(3))
        for ray in (RAY_DIFFUSE, RAY_GLOSSY, RAY_TRANSMISSION):
            chosen = np.flatnonzero(kinds == ray)
            if chosen.size == 0:
                continue
            group = _Group(rays, chosen)
            hit = self._query(ray, group, len(chosen), "closest")
            triangle[chosen], t[chosen], u[chosen], v[chosen] = hit
        return triangle, t, u, v

    def occluded(self, rays, count):
        return self._query(RAY_SHADOW, rays, count, "occluded")

    def intersect_before(self, rays, count):
        return self._query(RAY_SHADOW, rays, count, "before")


class _Group:
    """Some rays of a queue, as a queue of their own (contiguous float32 copies)."""

    def __init__(self, rays, chosen):
        self.origin = np.ascontiguousarray(rays.origin[chosen])
        self.direction = np.ascontiguousarray(rays.direction[chosen])
        self.tmax = np.ascontiguousarray(rays.tmax[chosen])
        self.path = np.arange(len(chosen), dtype=np.int32)  # ray j's time is time[j] (its path's)
        self.time = np.ascontiguousarray(rays.time[rays.path[chosen]])
