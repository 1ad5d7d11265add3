"""The ray-casting ceiling: how fast could a pass go if it only cast its rays?

We record every ray batch one pass of the renderer sends to its acceleration
structure (closest-hit and occlusion queries, with their origins, directions and
segment lengths), then replay exactly those batches on a bare embreex scene of the
same triangles, split into the same number of threads, and time only Embree's
``run``. The renderer's path throughput as a fraction of the ceiling is then

    fraction = (embreex time for the pass's rays) / (renderer time for a pass)

which is the same as (samples/s of the renderer) / (samples/s if casting the rays
were all the work). Recording is done on a separate pass that is not timed.
"""

from __future__ import annotations

import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np


class RayRecorder:
    """Wraps an object with ``intersect(o, d)`` / ``occluded(o, d, tmax)`` methods
    (engine.tracer.accel.Accel) and keeps copies of the batches while ``active``."""

    def __init__(self, accel):
        self.accel = accel
        self.batches: list[tuple[str, np.ndarray, np.ndarray, np.ndarray | None]] = []
        self.active = False
        self._intersect = accel.intersect
        self._occluded = accel.occluded
        accel.intersect = self._record_intersect
        accel.occluded = self._record_occluded

    def _record_intersect(self, origins, directions, *args, **kwargs):
        if self.active:
            self.batches.append(("closest", np.array(origins, np.float32), np.array(directions, np.float32), None))
        return self._intersect(origins, directions, *args, **kwargs)

    def _record_occluded(self, origins, directions, tmax, *args, **kwargs):
        if self.active:
            self.batches.append(
                ("occluded", np.array(origins, np.float32), np.array(directions, np.float32),
                 np.minimum(np.asarray(tmax, np.float64), 1e30).astype(np.float32))
            )
        return self._occluded(origins, directions, tmax, *args, **kwargs)

    def uninstall(self):
        self.accel.intersect = self._intersect
        self.accel.occluded = self._occluded

    @property
    def ray_count(self) -> int:
        return int(sum(len(b[1]) for b in self.batches))


def find_accel(renderer):
    """The renderer's acceleration object: the attribute with intersect + occluded."""
    for value in vars(renderer).values():
        if hasattr(value, "intersect") and hasattr(value, "occluded"):
            return value
    return None


def _clean(batch):
    kind, o, d, tmax = batch
    ok = np.isfinite(o).all(1) & np.isfinite(d).all(1) & ((d * d).sum(1) > 0)
    if tmax is not None:
        ok &= np.isfinite(tmax) & (tmax > 0)
    o, d = np.ascontiguousarray(o[ok]), np.ascontiguousarray(d[ok])
    return kind, o, d, (None if tmax is None else np.ascontiguousarray(tmax[ok]))


class Replayer:
    """Bare embreex scene of the same triangles, ready to cast recorded batches
    with ``threads`` threads (pieces of about 16,384 rays, as the renderer's Accel)."""

    def __init__(self, vertices, triangles, batches, threads: int):
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        self.scene = rtcore_scene.EmbreeScene()
        TriangleMesh(self.scene, np.ascontiguousarray(vertices, np.float32),
                     np.ascontiguousarray(triangles, np.int32))
        self.batches = [_clean(b) for b in batches]
        self.threads = threads
        self.pool = ThreadPoolExecutor(threads) if threads > 1 else None
        self.cast_all()  # warm-up: BVH build, first touch

    def _cast(self, kind, o, d, tmax):
        if kind == "closest":
            self.scene.run(o, d, output=1)
        else:
            self.scene.run(o, d, dists=tmax, query="OCCLUDED")

    def cast_all(self):
        """Cast every batch; with threads, all pieces of all batches go to the pool at
        once (the renderer also runs its chunks concurrently), so no thread idles
        while another finishes a batch."""
        if self.pool is None:
            for batch in self.batches:
                if len(batch[1]):
                    self._cast(*batch)
            return
        futures = []
        for kind, o, d, tmax in self.batches:
            n = len(o)
            if n == 0:
                continue
            parts = max(1, n // 16384)
            bounds = np.linspace(0, n, parts + 1).astype(int)
            futures += [
                self.pool.submit(self._cast, kind, o[a:b], d[a:b], None if tmax is None else tmax[a:b])
                for a, b in zip(bounds[:-1], bounds[1:])
            ]
        for f in futures:
            f.result()

    def seconds(self) -> float:
        """Wall time of one replay of every batch."""
        start = time.perf_counter()
        self.cast_all()
        return time.perf_counter() - start

    def close(self):
        if self.pool is not None:
            self.pool.shutdown()


def replay_seconds(vertices, triangles, batches, threads: int, repeats: int = 3) -> float:
    """Median wall time for bare embreex to cast ``batches`` with ``threads`` threads."""
    replayer = Replayer(vertices, triangles, batches, threads)
    try:
        return float(np.median([replayer.seconds() for _ in range(repeats)]))
    finally:
        replayer.close()


def synthetic_path_batches(scene, samples_per_pixel: int, depth: int, seed: int = 0):
    """Stand-in batches when a renderer cannot be recorded: pinhole camera rays
    through every pixel, then ``depth`` cosine-weighted bounces from the hits,
    plus one occlusion ray per hit towards the first light (same scene)."""
    from embreex import rtcore_scene
    from embreex.mesh_construction import TriangleMesh

    rng = np.random.default_rng(seed)
    es = rtcore_scene.EmbreeScene()
    TriangleMesh(es, scene.vertices, scene.triangles)
    cam = scene.camera
    w, h = cam.resolution
    n = w * h * samples_per_pixel
    xy = np.column_stack([rng.random(n) * w, rng.random(n) * h])
    x = (xy[:, 0] / w - 0.5) * cam.film_width_mm / cam.focal_length_mm
    y = (0.5 - xy[:, 1] / h) * cam.film_height_mm / cam.focal_length_mm
    d = np.column_stack([x, y, -np.ones(n)]) @ cam.camera_to_world[:3, :3].T
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    o = np.repeat(cam.camera_to_world[None, :3, 3], n, axis=0)
    light = scene.lights[0].position if scene.lights else np.zeros(3)
    batches = []
    for _ in range(depth + 1):
        o32, d32 = o.astype(np.float32), d.astype(np.float32)
        batches.append(("closest", o32, d32, None))
        r = es.run(o32, d32, output=1)
        hit = r["primID"] >= 0
        if not hit.any():
            break
        p = o[hit] + r["tfar"][hit, None] * d[hit]
        ng = r["Ng"][hit].astype(np.float64)
        ng /= np.linalg.norm(ng, axis=1, keepdims=True)
        ng *= -np.sign((ng * d[hit]).sum(1))[:, None]
        to_light = light - p
        dist = np.linalg.norm(to_light, axis=1)
        p_off = p + 1e-4 * ng
        batches.append(("occluded", p_off.astype(np.float32), (to_light / dist[:, None]).astype(np.float32),
                        (dist * 0.999).astype(np.float32)))
        # cosine-weighted bounce around the normal
        u1, u2 = rng.random(len(p)), rng.random(len(p))
        r_ = np.sqrt(u1)
        local = np.column_stack([r_ * np.cos(2 * np.pi * u2), r_ * np.sin(2 * np.pi * u2), np.sqrt(1 - u1)])
        a = np.where(np.abs(ng[:, :1]) > 0.9, [[0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0]])
        t = np.cross(a, ng)
        t /= np.linalg.norm(t, axis=1, keepdims=True)
        b = np.cross(ng, t)
        d = local[:, :1] * t + local[:, 1:2] * b + local[:, 2:] * ng
        o = p_off
    return batches
