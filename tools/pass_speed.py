"""How fast a render pass is against the embreex ceiling: ``python tools/pass_speed.py [scene] [threads]``.

Renders a benchmark scene (``benchmarks/scenes.py``: cornell_grey, cornell_glass, prism, lens,
soap_bubble, mesh_1m) in 64 x 64 passes of 16 spp, times the best of four passes after a warm-up,
records one pass's Embree queries and replays them on a bare embreex scene of the same triangles with
the same thread count. fraction = embreex time / pass time (1 = a pass does nothing but cast rays).
"""

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import numpy as np
from concurrent.futures import ThreadPoolExecutor
from benchmarks import scenes
from engine.tracer.renderer import Renderer
from engine.tracer.settings import RenderSettings

name = sys.argv[1] if len(sys.argv) > 1 else "cornell_glass"
threads = int(sys.argv[2]) if len(sys.argv) > 2 else 2
scene = scenes.build(name)
s = RenderSettings(samples=1000, samples_per_pass=16, seed=0, threads=threads)
t0 = time.perf_counter()
r = Renderer(scene, s)
print("setup", time.perf_counter() - t0)
r.render_pass()
times = []
for _ in range(4):
    t = time.perf_counter(); c = time.process_time()
    r.render_pass()
    times.append((time.perf_counter() - t, time.process_time() - c))
best = min(times)
print("pass wall/cpu", best, "rays/pass", r.stats["rays_cast"] / r._passes)
# record rays
batches = []
acc = r.tables.accel
orig = (acc.intersect, acc.occluded, acc.intersect_before)
def rec(kind, fn):
    def f(q, n):
        batches.append((kind, q.origin[:n].copy(), q.direction[:n].copy(), q.tmax[:n].copy()))
        return fn(q, n)
    return f
acc.intersect = rec("closest", orig[0]); acc.occluded = rec("occluded", orig[1]); acc.intersect_before = rec("before", orig[2])
r.render_pass()
acc.intersect, acc.occluded, acc.intersect_before = orig
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh
es = rtcore_scene.EmbreeScene()
TriangleMesh(es, r.tables.geometry.vertices, r.tables.geometry.triangles)
def replay(bs):
    for kind, o, d, tm in bs:
        if kind == "closest": es.run(o, d, output=1)
        elif kind == "before": es.run(o, d, dists=tm.copy(), output=1)
        else: es.run(o, d, dists=tm, query="OCCLUDED")
replay(batches)
nrays = sum(len(b[1]) for b in batches)
halves = [batches[0::2], batches[1::2]] if threads > 1 else [batches]
best_e = 1e9
with ThreadPoolExecutor(threads) as pool:
    for _ in range(5):
        t = time.perf_counter()
        list(pool.map(replay, halves))
        best_e = min(best_e, time.perf_counter() - t)
print(f"rays {nrays}  embree {best_e:.4f}s  pass {best[0]:.4f}s  fraction {best_e/best[0]:.1%}  paths/s {65536/best[0]:.0f}")
r.close()
