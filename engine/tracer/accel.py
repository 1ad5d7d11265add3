"""Ray queries against a render's geometry: closest hits and occlusion for queues of float32 rays.

Rays are traced by Prism's own Embree layer (``embree``): the scene is built once per geometry, and the
queries run in compiled code without the GIL, so the chunks traced by Prism's worker threads query it
concurrently. ``caster()`` is what compiled bounce loops pass to ``embree.queries`` to trace themselves.
Rays are always finite when they get here (the kernels that write queues drop non-finite rays: Embree
slows ~600x on NaN directions).
"""

from __future__ import annotations

import threading

import numpy as np


class Accel:
    """Queries against a ``geometry.Geometry`` (camera-relative float32 vertices; its spheres, rows after
    the triangles, as one more Embree geometry of sphere points, with the shutter's time steps where they move;
    its curve segments, rows after the spheres, as one of round Catmull-Rom curves)."""

    def __init__(self, geometry):
        from .embree.curves import CurveGeometry
        from .embree.scene import Scene, TriangleGeometry
        from .embree.spheres import SphereGeometry

        self._rows = {}  # RayCaster's id mapping; none: Embree's primitive ids are the rows
        moving = moving_triangles(geometry)
        if moving is None:
            geometries = [TriangleGeometry(geometry.vertices, geometry.triangles)] if len(geometry.triangles) else []
        else:  # static triangles as today (one time step), moving ones with the shutter's time steps
            static_rows, moving_rows = np.flatnonzero(~moving), np.flatnonzero(moving)
            geometries = []
            if len(static_rows):
                geometries.append(TriangleGeometry(geometry.vertices, geometry.triangles[static_rows]))
            geometries.append(TriangleGeometry(list(geometry.motion), geometry.triangles[moving_rows]))
            self._rows = dict(moving_geometry=len(geometries) - 1, first_moving=len(static_rows),
                              triangle_of=np.concatenate([static_rows, moving_rows]).astype(np.int32))
        if len(geometry.spheres):
            steps = list(geometry.sphere_motion) if len(geometry.sphere_motion) > 1 else geometry.spheres
            geometries.append(SphereGeometry(steps))
            self._rows.update(sphere_geometry=len(geometries) - 1, first_sphere=len(geometry.triangles))
        if len(geometry.curve_segments):
            steps = list(geometry.curve_motion) if len(geometry.curve_motion) > 1 else geometry.curves
            geometries.append(CurveGeometry(steps, geometry.curve_segments))
            self._rows.update(curve_geometry=len(geometries) - 1,
                              first_curve=len(geometry.triangles) + len(geometry.spheres),
                              curves=geometry.curves, curve_segments=geometry.curve_segments,
                              curve_motion=geometry.curve_motion)
        self._scene = Scene(geometries)
        self._local = threading.local()
        #: Chunks trace in compiled loops that query Embree themselves; False makes them call this
        #: object's query methods from Python instead (``benchmarks.ceiling`` records the rays that way).
        self.compiled_loops = True

    def caster(self):
        """This scene with this thread's ``RTCRayHit`` record (``embree.queries.RayCaster``), made once per thread."""
        found = getattr(self._local, "caster", None)
        if found is None:
            from .embree.layout import new_ray_hit_record
            from .embree.queries import RayCaster

            found = self._local.caster = RayCaster(self._scene.handle, *new_ray_hit_record(), **self._rows)
        return found

    def _closest(self, rays, count, bounded):
        from .embree.queries import closest_hits
        from .state import HitRecord

        hits = HitRecord(np.empty(count, np.int32), np.empty(count, np.float32), np.empty(count, np.float32),
                         np.empty(count, np.float32))
        closest_hits(self.caster(), _as_queue(rays), count, bounded, hits)
        return hits

    def intersect(self, rays, count):
        """Closest hits of the first ``count`` rays of ``rays`` (a ``state.RayQueue``):
        (triangle int32 [count] (-1: miss), t float32, u float32, v float32)."""
        return self._closest(rays, count, False)

    def intersect_before(self, rays, count):
        """Like ``intersect`` but only hits closer than ``rays.tmax`` (shadow rays crossing films)."""
        return self._closest(rays, count, True)

    def occluded(self, rays, count):
        """int32 [count]: 0 where something lies between the origin and ``tmax``, -1 where the ray is free."""
        from .embree.queries import occlusion

        result = np.empty(count, np.int32)
        occlusion(self.caster(), _as_queue(rays), count, result)
        return result


def moving_triangles(geometry):
    """bool [T]: the triangles whose corners move during the shutter, or None without motion blur (or
    when nothing moves)."""
    if geometry.motion.shape[0] < 2 or not len(geometry.triangles):
        return None
    still = (geometry.motion == geometry.motion[:1]).all(axis=(0, 2))  # per vertex, over the steps
    moving = ~still[geometry.triangles].all(axis=1)
    return moving if moving.any() else None


def _as_queue(rays):
    """``rays`` as a ``state.RayQueue`` (callers may hand any object with ``origin``, ``direction``, ``tmax``,
    and ``path`` / ``time`` where the rays have ray times)."""
    from .state import RayQueue

    if isinstance(rays, RayQueue):
        return rays
    n = len(rays.tmax)
    return RayQueue(getattr(rays, "path", np.zeros(n, np.int32)), rays.origin, rays.direction, rays.tmax,
                    getattr(rays, "time", np.full(max(n, 1), 0.5)))
