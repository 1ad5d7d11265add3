"""Ray visibility of objects: each kind of ray is traced against the triangles it can see.

embreex has no per-ray filters, so a scene where some object hides from some rays gets one Embree
scene per distinct set of visible triangles (most scenes: one or two), with the render's triangle id
of each of its triangles. A queue's rays are grouped by kind — camera rays until the path first scatters (through
cut-outs and films a camera ray stays one, as in Cycles: ``stages.bounces``), then by what the path's last
scattering was (``state.LAST_DIFFUSE``, ``LAST_TRANSMISSION``, else glossy) — and each group is traced against
its scene. Shadow rays see the shadow-visible triangles.

With a shadow catcher, the copies of camera paths that shade it for its pass (``state.CATCHER_PASS``,
``stages.shadow_catcher``) see only shadow catchers, each kind of ray the catchers visible to it, as Cycles
shifts their visibility (``SHADOW_CATCHER_PATH_VISIBILITY``); their shadow rays likewise.
"""

from __future__ import annotations

import numpy as np

from .accel import Accel
from .geometry import Geometry
from .stages.bounces import STEPS
from .state import CATCHER_PASS, LAST_DIFFUSE, LAST_TRANSMISSION
from .visibility import ALL_RAYS, RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_SHADOW, RAY_TRANSMISSION, SHADOW_CATCHER

_CLASSES = (RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_TRANSMISSION, RAY_SHADOW)


def needs_ray_classes(geometry) -> bool:
    """True when some triangle hides from some kind of ray, or some object is a shadow catcher (whose
    pass's paths see only catchers)."""
    flags = geometry.flags
    return bool(len(flags)) and bool(((flags & ALL_RAYS) != ALL_RAYS).any() or (flags & SHADOW_CATCHER).any())


class _Subset:
    """The rows ``chosen`` (triangles, then spheres, then curve segments) as a geometry of their own; ``ids`` its
    rows' render rows."""

    def __init__(self, geometry, chosen):
        self.ids = np.flatnonzero(chosen).astype(np.int32)
        count = len(geometry.triangles)
        spheres_end = count + len(geometry.spheres)
        triangles = self.ids[self.ids < count]
        spheres = self.ids[(self.ids >= count) & (self.ids < spheres_end)] - count
        segments = self.ids[self.ids >= spheres_end] - spheres_end
        sub = Geometry(geometry.vertices, np.ascontiguousarray(geometry.triangles[triangles]),
                       geometry.material[self.ids], geometry.normals[:0], geometry.attributes,
                       geometry.flags[self.ids], geometry.motion,
                       geometry.motion_normals[:, triangles] if len(geometry.motion_normals) else geometry.motion_normals,
                       np.ascontiguousarray(geometry.spheres[spheres]), geometry.sphere_random[spheres],
                       geometry.curves, np.ascontiguousarray(geometry.curve_segments[segments]),
                       geometry.curve_info[segments] if len(geometry.curve_info) else geometry.curve_info,
                       geometry.curve_motion,
                       geometry.sphere_motion[:, spheres] if len(geometry.sphere_motion) else geometry.sphere_motion,
                       geometry.terminator[:0])
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
        catcher = (geometry.flags & SHADOW_CATCHER) != 0
        self.catchers = bool(catcher.any())
        for ray in _CLASSES:
            for pass_path in ((False, True) if self.catchers else (False,)):
                chosen = (geometry.flags & ray) != 0
                if pass_path:
                    chosen &= catcher
                if chosen.all():
                    self._of_class[ray, pass_path] = None
                    continue
                key = chosen.tobytes()
                if key not in self._scenes:
                    self._scenes[key] = _Subset(geometry, chosen)
                self._of_class[ray, pass_path] = self._scenes[key]

    def _query(self, ray, rays, count, kind, pass_path=False):
        subset = self._of_class[ray, pass_path]
        accel = self._full if subset is None else subset.accel
        if kind == "occluded":
            return accel.occluded(rays, count)
        hit = accel.intersect(rays, count) if kind == "closest" else accel.intersect_before(rays, count)
        return hit if subset is None else subset._map(hit)

    def intersect(self, rays, count, state, depth):
        """Closest hits of the first ``count`` rays, each against what its kind of ray sees."""
        if depth == 0:  # camera rays: no path has met a shadow catcher yet
            return self._query(RAY_CAMERA, rays, count, "closest")
        paths = rays.path[:count]
        flags = state.flags[paths]
        scattered = np.where(flags & LAST_TRANSMISSION, RAY_TRANSMISSION,
                             np.where(flags & LAST_DIFFUSE, RAY_DIFFUSE, RAY_GLOSSY))
        kinds = np.where(depth == state.crossings[paths, STEPS], RAY_CAMERA, scattered)
        pass_paths = (flags & CATCHER_PASS) != 0
        triangle = np.empty(count, np.int32)
        t, u, v = (np.empty(count, np.float32) for _ in range(3))
        for ray in (RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_TRANSMISSION):
            for pass_path in ((False, True) if self.catchers else (False,)):
                chosen = np.flatnonzero((kinds == ray) & (pass_paths == pass_path))
                if chosen.size == 0:
                    continue
                group = _Group(rays, chosen)
                hit = self._query(ray, group, len(chosen), "closest", pass_path)
                triangle[chosen], t[chosen], u[chosen], v[chosen] = hit
        return triangle, t, u, v

    def occluded(self, rays, count, state=None):
        """Whether each of the first ``count`` shadow rays is blocked (``state``: the paths, whose catcher
        pass copies see only catchers; None: no such path)."""
        return self._shadow_query(rays, count, state, "occluded")

    def intersect_before(self, rays, count, state=None):
        return self._shadow_query(rays, count, state, "before")

    def _shadow_query(self, rays, count, state, kind):
        if not self.catchers or state is None:
            return self._query(RAY_SHADOW, rays, count, kind)
        pass_paths = (state.flags[rays.path[:count]] & CATCHER_PASS) != 0
        if not pass_paths.any():
            return self._query(RAY_SHADOW, rays, count, kind)
        out = None
        for pass_path in (False, True):
            chosen = np.flatnonzero(pass_paths == pass_path)
            if chosen.size == 0:
                continue
            got = self._query(RAY_SHADOW, _Group(rays, chosen), len(chosen), kind, pass_path)
            if kind == "occluded":
                if out is None:
                    out = np.empty(count, np.asarray(got).dtype)
                out[chosen] = got
            else:
                if out is None:
                    out = (np.empty(count, np.int32),) + tuple(np.empty(count, np.float32) for _ in range(3))
                for whole, part in zip(out, got):
                    whole[chosen] = part
        return out


class _Group:
    """Some rays of a queue, as a queue of their own (contiguous float32 copies)."""

    def __init__(self, rays, chosen):
        self.origin = np.ascontiguousarray(rays.origin[chosen])
        self.direction = np.ascontiguousarray(rays.direction[chosen])
        self.tmax = np.ascontiguousarray(rays.tmax[chosen])
        self.path = np.arange(len(chosen), dtype=np.int32)  # ray j's time is time[j] (its path's)
        self.time = np.ascontiguousarray(rays.time[rays.path[chosen]])
