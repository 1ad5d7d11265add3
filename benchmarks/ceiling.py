"""The ray-casting ceiling: how fast could a pass go if it only cast its rays?

We record every ray query one pass of the renderer sends to its ``engine.tracer.accel.Accel``
(``intersect``, ``intersect_before`` and ``occluded`` on a ``state.RayQueue``: float32 origins,
directions and, for shadow rays, ``tmax``), then replay exactly those batches on a bare embreex
scene of the renderer's own triangles (``renderer.tables.geometry``: camera-relative, as the rays
are) with the same number of threads, timing only Embree's ``run``. The renderer's path throughput
as a fraction of the ceiling is then

    fraction = (embreex time for the pass's rays) / (renderer time for a pass)

which is the same as (samples/s of the renderer) / (samples/s if casting the rays were all the
work). Recording is done on a separate pass that is not timed.
"""

from __future__ import annotations

import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

#: Query kinds, as recorded: closest hit, closest hit before ``tmax`` (shadow rays crossing films),
#: any hit before ``tmax`` (shadow rays).
CLOSEST, BEFORE, OCCLUDED = "closest", "before", "occluded"
QUERIES = {"intersect": CLOSEST, "intersect_before": BEFORE, "occluded": OCCLUDED}


class RayRecorder:
    """Wraps an ``Accel``'s query methods (on the instance) and keeps copies of the first ``count``
    rays of every queue they are given while ``active``: ``batches`` is a list of
    (kind, origin float32 [n, 3], direction float32 [n, 3], tmax float32 [n] or None)."""

    def __init__(self, accel):
        self.accel = accel
        self.batches: list[tuple[str, np.ndarray, np.ndarray, np.ndarray | None]] = []
        self.active = False
        self._originals = {name: getattr(accel, name) for name in QUERIES}
        self._own = {name for name in QUERIES if name in vars(accel)}  # already wrapped on the instance
        for name, kind in QUERIES.items():
            setattr(accel, name, self._recording(kind, self._originals[name]))
        self._compiled_loops = accel.compiled_loops
        accel.compiled_loops = False  # the chunks query Embree through the methods wrapped here

    def _recording(self, kind, query):
        def record(rays, count, *args, **kwargs):
            if self.active and count:
                tmax = None if kind == CLOSEST else rays.tmax[:count].copy()
                self.batches.append((kind, rays.origin[:count].copy(), rays.direction[:count].copy(), tmax))
            return query(rays, count, *args, **kwargs)

        return record

    def uninstall(self):
        self.accel.compiled_loops = self._compiled_loops
        for name in QUERIES:
            if name in self._own:
                setattr(self.accel, name, self._originals[name])
            else:
                delattr(self.accel, name)  # back to the class's method

    @property
    def ray_count(self) -> int:
        return int(sum(len(b[1]) for b in self.batches))

    def count(self, kind: str) -> int:
        return int(sum(len(b[1]) for b in self.batches if b[0] == kind))


def record_pass(renderer) -> RayRecorder:
    """Render one pass of ``renderer`` with its queries recorded (the pass is not timed)."""
    recorder = RayRecorder(renderer.tables.accel)
    try:
        recorder.active = True
        renderer.render_pass()
    finally:
        recorder.active = False
        recorder.uninstall()
    return recorder


class Replayer:
    """A bare embreex scene of the renderer's triangles, ready to cast recorded batches with
    ``threads`` threads (each batch cut into pieces of about 16,384 rays)."""

    PIECE = 16384

    def __init__(self, geometry, batches, threads: int):
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        self.scene = rtcore_scene.EmbreeScene()
        TriangleMesh(self.scene, np.ascontiguousarray(geometry.vertices, np.float32),
                     np.ascontiguousarray(geometry.triangles, np.int32))
        self.batches = [b for b in batches if len(b[1])]
        self.threads = threads
        self.pool = ThreadPoolExecutor(threads) if threads > 1 else None
        self.cast_all()  # warm-up: BVH build, first touch

    def _cast(self, kind, o, d, tmax):
        if kind == CLOSEST:
            self.scene.run(o, d, output=1)
        elif kind == BEFORE:
            self.scene.run(o, d, dists=tmax.copy(), output=1)  # embreex writes tfar into dists
        else:
            self.scene.run(o, d, dists=tmax, query="OCCLUDED")

    def cast_all(self):
        """Cast every batch; with threads, all pieces of all batches go to the pool at once (the
        renderer also runs its chunks concurrently), so no thread idles while another finishes."""
        if self.pool is None:
            for batch in self.batches:
                self._cast(*batch)
            return
        futures = []
        for kind, o, d, tmax in self.batches:
            parts = max(1, len(o) // self.PIECE)
            bounds = np.linspace(0, len(o), parts + 1).astype(int)
            futures += [self.pool.submit(self._cast, kind, o[a:b], d[a:b], None if tmax is None else tmax[a:b])
                        for a, b in zip(bounds[:-1], bounds[1:])]
        for f in futures:
            f.result()

    def seconds(self) -> float:
        """Wall time of one replay of every batch."""
        start = time.perf_counter()
        self.cast_all()
        return time.perf_counter() - start

    def cpu_seconds(self) -> float:
        """Process CPU time of one replay of every batch."""
        start = time.process_time()
        self.cast_all()
        return time.process_time() - start

    def close(self):
        if self.pool is not None:
            self.pool.shutdown()
