"""Ray queries with embreex (Embree 4): closest hits and occlusion for a queue of float32 rays.

Embree's ``run`` releases the GIL, so the chunks traced by Prism's worker threads query it
concurrently; each call traces one queue serially. Rays are always finite when they get here (the
kernels that write queues drop non-finite rays: Embree slows ~600x on NaN directions).
"""

from __future__ import annotations

import numpy as np


class Accel:
    """Queries against a ``geometry.Geometry`` (camera-relative float32 vertices)."""

    def __init__(self, geometry):
        self._scene = None
        if len(geometry.triangles):
            from embreex import rtcore_scene
            from embreex.mesh_construction import TriangleMesh

            self._scene = rtcore_scene.EmbreeScene()
            TriangleMesh(self._scene, geometry.vertices, geometry.triangles)

    def intersect(self, rays, count):
        """Closest hits of the first ``count`` rays of ``rays`` (a ``state.RayQueue``):
        (triangle int32 [count] (-1: miss), t float32, u float32, v float32)."""
        if self._scene is None or count == 0:
            return (np.full(count, -1, np.int32), np.full(count, np.inf, np.float32),
                    np.zeros(count, np.float32), np.zeros(count, np.float32))
        r = self._scene.run(rays.origin[:count], rays.direction[:count], output=1)
        return r["primID"], r["tfar"], r["u"], r["v"]

    def intersect_before(self, rays, count):
        """Like ``intersect`` but only hits closer than ``rays.tmax`` (shadow rays crossing films)."""
        if self._scene is None or count == 0:
            return (np.full(count, -1, np.int32), np.full(count, np.inf, np.float32),
                    np.zeros(count, np.float32), np.zeros(count, np.float32))
        r = self._scene.run(rays.origin[:count], rays.direction[:count], dists=rays.tmax[:count].copy(), output=1)
        return r["primID"], r["tfar"], r["u"], r["v"]

    def occluded(self, rays, count):
        """int32 [count]: 0 where something lies between the origin and ``tmax``, -1 where the ray is free."""
        if self._scene is None or count == 0:
            return np.full(count, -1, np.int32)
        return self._scene.run(rays.origin[:count], rays.direction[:count], dists=rays.tmax[:count], query="OCCLUDED")
