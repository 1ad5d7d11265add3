"""Thread scaling next to bare Embree's on the same rays, at every thread count up to every core.

    .venv/bin/python -m benchmarks.scaling [--quick] [--threads 1 2 4 ...] [--json FILE]

For each scene (cornell_glass, mesh_1m) and pass size (a small pass, as the viewport and the first passes
of F12 render, and a large one), one pass is rendered with its Embree queries recorded
(``benchmarks.ceiling``), then renderer passes with T threads and embreex replays of exactly those rays
with T threads alternate, ``rounds`` times per T. Reported per T: Prism's paths per second, its speed-up
over T = 1, embreex's speed-up on the same rays, and the share of Embree's scaling Prism keeps
(Prism's speed-up / embreex's). The thread counts are 1, 2, 4, ... up to the machine's cores, the core
count itself, and 8 and 16 where the machine has fewer cores (oversubscribed: no slower than T = 2 is
the target there; Prism runs one worker thread per core for them, ``chunk_pool.worker_threads``).

The GIL share: for T = 1 and 2, the process CPU time of a pass against the CPU time its threads spend
inside the compiled chunk calls (``stages.trace`` and ``stages.light_trace``'s kernels, which release
the GIL); the rest (chunk bookkeeping, the film's ``add`` on the main thread, the pool) is counted as
time holding the GIL, an upper bound since numpy releases it inside large operations.
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import time

import numpy as np

from . import ceiling, scenes
from .findings_values import _pct, _status
from .prism_runs import settings_for
from .targets import TARGET_SCALING_KEPT

#: (scene, pass name, resolution, samples per pixel of a pass)
FULL_CASES = [("cornell_glass", "small", 384, 1), ("cornell_glass", "large", 1024, 4),
              ("mesh_1m", "small", 384, 1), ("mesh_1m", "large", 1024, 4)]
QUICK_CASES = [("cornell_glass", "small", 128, 1), ("mesh_1m", "small", 128, 1)]
#: the stage modules whose compiled calls release the GIL, and the names of those calls
_COMPILED_CALLS = {"stages.trace": ("camera_kernel", "real_lens_kernel", "reset_kernel", "bounce_loop_kernel"),
                   "stages.light_trace": ("light_loop_kernel",)}


def thread_counts(cores: int) -> list[int]:
    """1, 2, 4, ... up to ``cores``, ``cores`` itself, and 8 and 16 beyond a smaller machine's cores."""
    counts, t = [], 1
    while t <= cores:
        counts.append(t)
        t *= 2
    counts += [cores, 8, 16]
    return sorted(set(counts))


class _KernelClock:
    """Thread CPU time spent inside the compiled chunk calls while installed (see the module docstring)."""

    def __init__(self, tracer_package: str):
        self.cpu = 0.0
        self._modules = {importlib.import_module(f"{tracer_package}.{name}"): calls
                         for name, calls in _COMPILED_CALLS.items()}
        self._saved = {}

    def _timed(self, function):
        def call(*args):
            start = time.thread_time()
            try:
                return function(*args)
            finally:
                self.cpu += time.thread_time() - start  # float += is atomic enough under the GIL

        return call

    def __enter__(self):
        for module, calls in self._modules.items():
            for name in calls:
                self._saved[(module, name)] = getattr(module, name)
                setattr(module, name, self._timed(self._saved[(module, name)]))
        return self

    def __exit__(self, *exc):
        for (module, name), function in self._saved.items():
            setattr(module, name, function)


def gil_share(renderer, passes: int = 3) -> float:
    """Share of the process CPU time of ``passes`` passes of ``renderer`` spent outside the compiled chunk
    calls (holding the GIL, or waiting for it)."""
    package = type(renderer).__module__.rsplit(".", 1)[0]
    with _KernelClock(package) as clock:
        start = time.process_time()
        for _ in range(passes):
            renderer.render_pass()
        total = time.process_time() - start
    return max(0.0, 1.0 - clock.cpu / total) if total > 0 else float("nan")


def measure_case(name: str, label: str, resolution: int, spp: int, counts, rounds: int, log=print) -> dict:
    """The scaling table of one scene and pass size (see the module docstring)."""
    from engine.tracer.renderer import Renderer

    scene = scenes.build(name, (resolution, resolution))
    renderers = {}
    try:
        for t in counts:
            renderers[t] = Renderer(scene, settings_for({"samples_per_pass": spp}, samples=10**7, seed=11, threads=t))
            renderers[t].render_pass()  # warm-up: kernels, first touch of the buffers
        recorder = ceiling.record_pass(renderers[counts[0]])
        paths = resolution * resolution * spp
        prism = {t: [] for t in counts}
        embree = {t: [] for t in counts}
        replayers = {t: ceiling.Replayer(renderers[counts[0]].tables.geometry, recorder.batches, t) for t in counts}
        try:
            for _ in range(rounds):
                for t in counts:  # interleaved, so load from elsewhere hits every T alike
                    start = time.perf_counter()
                    renderers[t].render_pass()
                    prism[t].append(time.perf_counter() - start)
                    embree[t].append(replayers[t].seconds())
        finally:
            for replayer in replayers.values():
                replayer.close()
        shares = {t: gil_share(renderers[t]) for t in counts if t <= 2}
    finally:
        for renderer in renderers.values():
            renderer.close()
    p = {t: float(np.median(v)) for t, v in prism.items()}
    e = {t: float(np.median(v)) for t, v in embree.items()}
    first = counts[0]
    rows = []
    for t in counts:
        prism_speedup, embree_speedup = p[first] / p[t], e[first] / e[t]
        rows.append(dict(threads=t, prism_seconds=p[t], embree_seconds=e[t], paths_per_second=paths / p[t],
                         prism_speedup=prism_speedup, embree_speedup=embree_speedup,
                         kept=prism_speedup / embree_speedup, oversubscribed=t > (os.cpu_count() or 1)))
        log(f"{name} {label} T={t}: {paths / p[t]:,.0f} paths/s, x{prism_speedup:.2f} (embreex x{embree_speedup:.2f})")
    return dict(scene=name, label=label, resolution=resolution, spp=spp, paths=paths, rays=recorder.ray_count,
                rounds=rounds, rows=rows, gil_share={str(t): s for t, s in shares.items()},
                all_prism={str(t): v for t, v in prism.items()}, all_embree={str(t): v for t, v in embree.items()})


def measure_scaling(quick: bool = False, counts=None, rounds: int | None = None, log=print) -> dict:
    """Every case of ``FULL_CASES`` (``QUICK_CASES`` with ``quick``) at ``counts`` threads."""
    counts = sorted(set(counts or thread_counts(os.cpu_count() or 1)))
    rounds = rounds or (2 if quick else 3)
    cases = [measure_case(*case, counts, rounds, log=log) for case in (QUICK_CASES if quick else FULL_CASES)]
    return dict(cores=os.cpu_count(), counts=counts, cases=cases)


MIN_EMBREE_SCALING = 1.3  # below this, embreex's own speed-up says the other cores were busy


def target_row(case: dict, cores: int) -> str:
    """The targets' row of one scaling case: >= 85 % of embreex's scaling at every T up to the cores,
    and never slower with more threads (oversubscribed T no slower than T = 2)."""
    rows = case["rows"]
    inside = [r for r in rows if r["threads"] > 1 and not r["oversubscribed"]]
    two = next((r for r in rows if r["threads"] == 2), None)
    measurable = all(r["embree_speedup"] >= MIN_EMBREE_SCALING for r in inside)
    kept_ok = all(r["kept"] >= TARGET_SCALING_KEPT for r in inside)
    monotone = all(b["paths_per_second"] >= 0.95 * a["paths_per_second"] for a, b in zip(rows, rows[1:])
                   if not b["oversubscribed"])
    over_ok = two is None or all(r["paths_per_second"] >= 0.95 * two["paths_per_second"] for r in rows
                                 if r["oversubscribed"])
    least = min(inside, key=lambda r: r["kept"]) if inside else None
    figures = "; ".join(f"T={r['threads']} x{r['prism_speedup']:.2f} / embreex x{r['embree_speedup']:.2f}"
                        for r in rows if r["threads"] > 1)
    status = (_status(kept_ok and monotone and over_ok) if measurable else
              "not measurable in this run (embreex itself did not scale: the cores were busy)")
    least_text = f"least {_pct(least['kept'])} of embreex's scaling; " if least else ""
    return (f"| scaling >= {TARGET_SCALING_KEPT:.0%} of embreex's at every T <= {cores}, never slower with "
            f"more threads ({case['scene']}, {case['label']} pass) | {least_text}{figures} | {status} |")


def scaling_table(result: dict) -> str:
    """The markdown table of ``measure_scaling``'s result: paths/s and speed-ups per T, per case."""
    counts = result["counts"]
    header = "| case | | " + " | ".join(f"T={t}" + ("*" if t > result["cores"] else "") for t in counts) + " |"
    lines = [header, "|---|---|" + "---:|" * len(counts)]
    for case in result["cases"]:
        rows = {r["threads"]: r for r in case["rows"]}
        title = f"{case['scene']} {case['resolution']}x{case['resolution']}, {case['spp']} spp"
        lines.append(f"| {title} | Prism paths/s | " + " | ".join(f"{rows[t]['paths_per_second']:,.0f}" for t in counts)
                     + " |")
        lines.append("| | Prism x T=1 | " + " | ".join(f"{rows[t]['prism_speedup']:.2f}" for t in counts) + " |")
        lines.append("| | embreex x T=1, same rays | " + " | ".join(f"{rows[t]['embree_speedup']:.2f}" for t in counts)
                     + " |")
        lines.append("| | Prism / embreex scaling | " + " | ".join(f"{rows[t]['kept']:.0%}" for t in counts) + " |")
    shares = [f"{c['scene']} {c['label']}: " + ", ".join(f"T={t} {s:.1%}" for t, s in c["gil_share"].items())
              for c in result["cases"]]
    lines += ["", f"\\* more threads than the machine's {result['cores']} cores: Prism runs one worker per core "
              "(`chunk_pool.worker_threads`), embreex's replay all T.", "",
              "Share of a pass's CPU time outside the compiled chunk calls (GIL held or awaited): " + "; ".join(shares)
              + "."]
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="128x128 small passes only, two rounds")
    parser.add_argument("--threads", type=int, nargs="*", help="thread counts (default: see thread_counts)")
    parser.add_argument("--rounds", type=int)
    parser.add_argument("--json", help="also write the result here")
    args = parser.parse_args(argv)
    result = measure_scaling(args.quick, args.threads, args.rounds)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(result, f, indent=1)
    print(scaling_table(result))
    return 0


if __name__ == "__main__":
    from engine.batch.process_exit import exit_now

    exit_now(main())
