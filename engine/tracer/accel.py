"""Ray-triangle queries on batches with embreex (Embree 4), split over threads.

Embree's ``run`` releases the GIL, so chunks of one batch run concurrently in a
thread pool. Rays with a non-finite origin or direction are never sent to Embree:
they report a miss (and are counted in ``rejected_rays``). Zero-area and
non-finite triangles are dropped when the scene is built; hit indices are always
those of the caller's triangle array.
"""

from __future__ import annotations

import os
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .sampling import dot, rows_finite

_MIN_CHUNK = 16384
REJECTED = -2  # triangle index reported for rays that were not sent (non-finite)
_FAR = np.float32(1e30)


def _threads(requested: int) -> int:
    return max(1, int(requested) if requested and requested > 0 else (os.cpu_count() or 1))


class Accel:
    """Closest-hit and occlusion queries against a triangle soup.

    ``vertices`` float [V,3] (m), ``triangles`` int [T,3]. ``threads`` 0 = all cores.
    """

    def __init__(self, vertices: np.ndarray, triangles: np.ndarray, threads: int = 0):
        vertices = np.ascontiguousarray(vertices, dtype=np.float32)
        triangles = np.ascontiguousarray(triangles, dtype=np.int32).reshape(-1, 3)
        corners = vertices[triangles].astype(np.float64) if len(triangles) else np.zeros((0, 3, 3))
        cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        double_area = np.linalg.norm(cross, axis=1)
        keep = np.isfinite(double_area) & (double_area > 0.0)
        self.dropped_triangles = int((~keep).sum())
        self.kept_triangles = np.flatnonzero(keep).astype(np.int64)
        self.threads = _threads(threads)
        self.rejected_rays = 0
        self._lock = threading.Lock()
        self._pool = ThreadPoolExecutor(self.threads) if self.threads > 1 else None
        self._scene = None
        if len(self.kept_triangles):
            from embreex import rtcore_scene
            from embreex.mesh_construction import TriangleMesh

            self._scene = rtcore_scene.EmbreeScene()
            TriangleMesh(self._scene, vertices, np.ascontiguousarray(triangles[keep]))

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=False)
            self._pool = None

    def _split(self, n: int) -> list[slice]:
        parts = min(self.threads, max(1, n // _MIN_CHUNK))
        bounds = np.linspace(0, n, parts + 1).astype(int)
        return [slice(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]

    def _map(self, fn, n: int) -> list:
        slices = self._split(n)
        if self._pool is None or len(slices) == 1:
            return [fn(s) for s in slices]
        return list(self._pool.map(fn, slices))

    def _prepare(self, origins, directions, tmax=None):
        o = np.asarray(origins, dtype=np.float32)
        d = np.asarray(directions, dtype=np.float32)
        ok = rows_finite(o) & rows_finite(d) & (dot(d, d) > 0)
        if tmax is not None:
            tmax = np.minimum(np.asarray(tmax, dtype=np.float64), 1e30)
            ok &= ~np.isnan(tmax) & (tmax > 0)
        bad = int((~ok).sum())
        if bad:
            with self._lock:
                self.rejected_rays += bad
            idx = np.flatnonzero(ok)
            o, d = o[idx], d[idx]
            tmax = None if tmax is None else tmax[idx]
        else:
            idx = None
        o = np.ascontiguousarray(o)
        d = np.ascontiguousarray(d)
        if tmax is not None:
            tmax = np.ascontiguousarray(tmax, dtype=np.float32)
        return o, d, tmax, idx

    def intersect(self, origins: np.ndarray, directions: np.ndarray):
        """Closest hits of rays [N,3] (any float dtype; directions need not be unit).

        Returns ``(triangle int64 [N] (-1 = miss, -2 = ray not sent: non-finite), t float64 [N] (inf on miss),
        u float64 [N], v float64 [N])``; the hit point is o + t d, barycentric
        corner weights (1-u-v, u, v).
        """
        n = len(origins)
        tri = np.full(n, -1, dtype=np.int64)
        t = np.full(n, np.inf)
        u = np.zeros(n)
        v = np.zeros(n)
        if n and self._scene is None:
            finite = np.isfinite(origins).all(axis=1) & np.isfinite(directions).all(axis=1)
            tri[~finite] = REJECTED
        if self._scene is None or n == 0:
            return tri, t, u, v
        o, d, _, idx = self._prepare(origins, directions)
        m = len(o)
        prim = np.empty(m, dtype=np.int64)
        tf = np.empty(m, dtype=np.float64)
        uu = np.empty(m)
        vv = np.empty(m)

        def work(s):
            r = self._scene.run(o[s], d[s], output=1)
            prim[s] = r["primID"]
            tf[s] = r["tfar"]
            uu[s] = r["u"]
            vv[s] = r["v"]

        self._map(work, m)
        hit = prim >= 0
        if self.dropped_triangles:
            prim_out = np.where(hit, self.kept_triangles[np.where(hit, prim, 0)], -1)
        else:  # Embree's ids are ours
            prim_out = np.where(hit, prim, -1)
        tf[~hit] = np.inf
        if idx is None:
            return prim_out, tf, uu, vv
        tri[:] = REJECTED
        tri[idx], t[idx], u[idx], v[idx] = prim_out, tf, uu, vv
        return tri, t, u, v

    def occluded(self, origins: np.ndarray, directions: np.ndarray, tmax: np.ndarray) -> np.ndarray:
        """True where any triangle lies on the segment o + t d, 0 < t < ``tmax`` [N].
        Rays that cannot be sent (non-finite) count as occluded, so they add nothing."""
        n = len(origins)
        if n == 0:
            return np.zeros(0, dtype=bool)
        if self._scene is None:
            return ~(np.isfinite(origins).all(1) & np.isfinite(directions).all(1))
        o, d, tm, idx = self._prepare(origins, directions, tmax)
        m = len(o)
        out = np.empty(m, dtype=bool)

        def work(s):
            out[s] = self._scene.run(o[s], d[s], dists=tm[s], query="OCCLUDED") != -1

        self._map(work, m)
        if idx is None:
            return out
        full = np.ones(n, dtype=bool)
        full[idx] = out
        return full
