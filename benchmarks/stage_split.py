"""Where a pass spends its time: CPU time (and wall time) per stage kernel and per Embree query.

The stage kernels are called by ``engine.tracer.stages.trace`` through its module namespace, and the
Embree queries through ``renderer.tables.accel``: for the measured passes both are replaced by timing
wrappers (``thread_time`` and ``perf_counter`` around each call, a handful per chunk and bounce), and
restored afterwards. Chunks run the stepwise loop for these passes (``Accel.compiled_loops`` off:
the same kernels, called from Python, so each can be timed; the compiled bounce loop runs them in one
call); the timed passes of the harness never run wrapped.

CPU time of the calling thread is what a stage costs, whatever else the machine runs (a thread that
is descheduled inside a kernel accrues wall time, not CPU time); shares are of the CPU time of all
chunks of the pass. With several threads, a stage whose CPU time per pass grows against one thread
is slowed by the other thread (memory bandwidth, shared caches). The wall-clock side: the pass's
wall time, and how much of threads x wall the chunks' CPU time leaves unexplained (idle threads,
waiting for the last chunk, the pool, other processes).
"""

from __future__ import annotations

import importlib
import threading
import time
from contextlib import contextmanager
from dataclasses import replace

from .prism_runs import PASS_SPP, settings_for

#: (stage name in the report, names in ``stages.trace`` timed as that stage)
KERNEL_STAGES = [
    ("camera rays", ("camera_kernel", "real_lens_kernel")),
    ("emission (hits and escapes)", ("emission_kernel",)),
    ("shade (BSDF, light sampling, roulette)", ("shade_kernel",)),
    ("shadow results", ("shadow_kernel",)),
    ("film layers of shadow rays", ("film_layer_kernel",)),
    ("film (spectrum to RGB per path)", ("film_kernel",)),
]
EMBREE_STAGES = [
    ("Embree closest hits", ("intersect",)),
    ("Embree shadow rays", ("occluded", "intersect_before")),
]
CHUNK = "trace_chunk"
PYTHON_BETWEEN = "Python between kernels (trace_chunk)"
FILM_ADD = "film.add (main thread, outside the chunks)"


class _Clock:
    """CPU and wall seconds and calls per name, from any thread."""

    def __init__(self):
        self.cpu: dict[str, float] = {}
        self.wall: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        self._lock = threading.Lock()

    def wrap(self, name, function):
        def timed(*args, **kwargs):
            wall, cpu = time.perf_counter(), time.thread_time()
            try:
                return function(*args, **kwargs)
            finally:
                cpu, wall = time.thread_time() - cpu, time.perf_counter() - wall
                with self._lock:
                    self.cpu[name] = self.cpu.get(name, 0.0) + cpu
                    self.wall[name] = self.wall.get(name, 0.0) + wall
                    self.calls[name] = self.calls.get(name, 0) + 1

        return timed


def _tracer(scene) -> str:
    """The tracer package ``scene`` belongs to: ``engine.tracer``, or the add-on's copy
    (``prism_spectral.engine.tracer``) for a scene exported from Blender by the add-on."""
    return type(scene).__module__.rsplit(".", 1)[0]


@contextmanager
def timed_stages(renderer, clock: _Clock):
    """Replace the stage kernels (module ``stages.trace`` of the renderer's tracer), the accel's queries
    and the film's ``add`` of ``renderer`` by timing wrappers for the duration of the block."""
    trace = importlib.import_module(type(renderer).__module__.rsplit(".", 1)[0] + ".stages.trace")
    module_names = [n for _, names in KERNEL_STAGES for n in names] + [CHUNK]
    saved_module = {n: getattr(trace, n) for n in module_names}
    accel_names = [n for _, names in EMBREE_STAGES for n in names]
    saved_accel = {n: getattr(renderer.tables.accel, n) for n in accel_names}
    saved_add = renderer.film.add
    renderer.tables.accel.compiled_loops = False
    try:
        for n in module_names:
            setattr(trace, n, clock.wrap(n, saved_module[n]))
        for n in accel_names:
            setattr(renderer.tables.accel, n, clock.wrap(n, saved_accel[n]))
        renderer.film.add = clock.wrap("film.add", saved_add)
        yield
    finally:
        for n, f in saved_module.items():
            setattr(trace, n, f)
        for n in accel_names:
            delattr(renderer.tables.accel, n)  # back to the class's methods
        renderer.tables.accel.compiled_loops = True
        del renderer.film.add


def stage_split(scene, overrides: dict, threads: int, passes: int = 3, seed: int = 5, settings=None) -> dict:
    """Per pass (mean over ``passes`` wrapped passes after an unwrapped warm-up pass): ``rows``
    [{stage, cpu, wall, calls, share}] for every stage kernel, Embree, the Python around them in the
    chunks and ``film.add`` (share = of ``chunk_cpu``, the CPU time of all chunks; ``film.add`` runs on
    the main thread, outside the chunks); ``pass_seconds`` (wall), ``chunk_cpu``, ``chunk_wall``,
    ``unexplained`` = threads x pass wall - chunk CPU (idle, waits, descheduled), ``threads``,
    ``paths``. ``settings`` (else the harness's, with ``overrides``) get the samples, seed and threads."""
    samples = PASS_SPP * (passes + 2)
    if settings is None:
        settings = settings_for(overrides, samples=samples, seed=seed, threads=threads)
    else:
        settings = replace(settings, samples=settings.samples_per_pass * (passes + 2), seed=seed, threads=threads)
    renderer = importlib.import_module(_tracer(scene) + ".renderer").Renderer(scene, settings)
    clock = _Clock()
    try:
        renderer.render_pass()  # warm-up: kernels loaded, buffers allocated
        wall = 0.0
        with timed_stages(renderer, clock):
            for _ in range(passes):
                start = time.perf_counter()
                renderer.render_pass()
                wall += time.perf_counter() - start
        paths = renderer.stats["paths"] // renderer._passes if renderer._passes else 0
    finally:
        renderer.close()
    cpu = {k: v / passes for k, v in clock.cpu.items()}
    walls = {k: v / passes for k, v in clock.wall.items()}
    calls = {k: v / passes for k, v in clock.calls.items()}
    wall /= passes
    rows = []
    inside_cpu = inside_wall = 0.0
    for label, names in KERNEL_STAGES + EMBREE_STAGES:
        if not any(n in cpu for n in names):
            continue
        row = dict(stage=label, cpu=sum(cpu.get(n, 0.0) for n in names), wall=sum(walls.get(n, 0.0) for n in names),
                   calls=sum(calls.get(n, 0) for n in names))
        inside_cpu += row["cpu"]
        inside_wall += row["wall"]
        rows.append(row)
    chunk_cpu, chunk_wall = cpu.get(CHUNK, 0.0), walls.get(CHUNK, 0.0)
    rows.append(dict(stage=PYTHON_BETWEEN, cpu=max(chunk_cpu - inside_cpu, 0.0),
                     wall=max(chunk_wall - inside_wall, 0.0), calls=calls.get(CHUNK, 0)))
    for row in rows:
        row["share"] = row["cpu"] / chunk_cpu if chunk_cpu > 0 else float("nan")
    rows.append(dict(stage=FILM_ADD, cpu=cpu.get("film.add", 0.0), wall=walls.get("film.add", 0.0),
                     calls=calls.get("film.add", 0), share=float("nan")))
    return dict(threads=threads, pass_seconds=wall, paths=int(paths), chunk_cpu=chunk_cpu, chunk_wall=chunk_wall,
                unexplained=max(threads * wall - chunk_cpu, 0.0), rows=rows)
