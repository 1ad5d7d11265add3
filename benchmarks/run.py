"""Speed against error: ``python -m benchmarks.run [--quick] [--scenes a b ...]``.

For each scene: cached high-sample references, then for each strategy (the Sobol sampler's
counterpart with independent random numbers among them) a progressive render (median of ``repeats``
seeds) with wall time and relMSE / FLIP at each checkpoint; the embreex ceiling on the rays of one
pass; the time of a pass split by stage kernel; thread scaling up to every core next to embreex's on
the same rays (``scaling``); cold-compile and warm-start seconds; the peers (Mitsuba 3, Cycles) on the scenes they can render;
the demo render now and before the compiled core; the experiments of ``benchmarks/experiments/``.
Writes benchmarks/results/results.json, table.md, *.png and docs/performance.md. This module holds
the entry point (arguments, warm-up, the order of the parts); the measuring functions are in
``measure.py``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import sys
import time
import warnings
from pathlib import Path

from . import demo, experiments, metrics, references, report, scaling, scenes, startup
from .measure import (EXPERIMENTS, THREADS, log, measure_ceiling, measure_stage_split, run_peers, run_scene,
                      scene_config)
from .prism_runs import PASS_SPP, progressive, settings_for

RESULTS_DIR = references.BENCH_DIR / "results"

# References have at least 8x the samples of any image scored against them (the equal-time curves
# for the peers stop there too), so their own noise adds at most ~1/8 to a measured relMSE.
FULL = dict(resolution=64, checkpoints=[4, 8, 16, 32, 64, 128], repeats=3, ref_spp=2048, ref_max_seconds=150.0,
            peer_spp={"mitsuba": [4, 8, 16, 32, 64, 128, 256, 512], "cycles": [4, 8, 16, 32, 64, 128]},
            peer_ref_spp={"mitsuba": 8192, "cycles": 1024}, ceiling_passes=3, scaling_rounds=5,
            per_scene={"prism": dict(resolution=32, checkpoints=[16, 32, 64, 128, 256, 512], ref_spp=4096,
                                     ref_max_seconds=150.0),
                       "cornell_grey": dict(ref_spp=8192, ref_max_seconds=240.0),
                       "mesh_1m": dict(ref_spp=4096, ref_max_seconds=240.0,
                                       peer_spp={"mitsuba": [4, 8, 16, 32, 64, 128, 256, 512]},
                                       peer_ref_spp={"mitsuba": 4096})})
QUICK = dict(resolution=32, checkpoints=[2, 4, 8, 16], repeats=2, ref_spp=256, ref_max_seconds=30.0,
             peer_spp={"mitsuba": [2, 4, 8, 16, 32, 64], "cycles": [2, 4, 8, 16, 32, 64]},
             peer_ref_spp={"mitsuba": 2048, "cycles": 512}, ceiling_passes=2, scaling_rounds=2,
             per_scene={"prism": dict(resolution=24, checkpoints=[8, 16, 32, 64, 128], ref_spp=1024,
                                      ref_max_seconds=40.0)})


def _section(results, name):
    """Log the start of a part of the run with the machine's load average at that moment."""
    load = os.getloadavg()[0]
    results["machine"].setdefault("load_by_section", []).append([name, load])
    log(f"{name} (load {load:.1f})")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="32x32, fewer samples and repeats")
    parser.add_argument("--scenes", nargs="*", default=list(EXPERIMENTS), choices=list(EXPERIMENTS))
    parser.add_argument("--no-peers", action="store_true")
    parser.add_argument("--no-demo", action="store_true", help="skip the demo render (now and before)")
    parser.add_argument("--docs", default=None,
                        help="document to write (default docs/performance.md; with --quick "
                             "benchmarks/results/quick/performance.md)")
    parser.add_argument("--report-only", action="store_true",
                        help="rewrite the tables, plots and document from results/results.json")
    args = parser.parse_args(argv)
    # a quick run never overwrites the committed full results
    results_dir = RESULTS_DIR / "quick" if args.quick else RESULTS_DIR
    docs = Path(args.docs) if args.docs else (
        results_dir / "performance.md" if args.quick else references.REPO_ROOT / "docs" / "performance.md")
    if args.report_only:
        results = json.loads((results_dir / "results.json").read_text())
        report.write_all(results, {}, results_dir, docs)
        log(f"rewrote {results_dir} and {docs} from results.json")
        return 0
    cfg = QUICK if args.quick else FULL
    warnings.simplefilter("ignore", RuntimeWarning)
    started = time.perf_counter()
    results = dict(config=dict(cfg, quick=args.quick, threads=THREADS, pass_spp=PASS_SPP,
                               relmse_epsilon=metrics.RELMSE_EPSILON),
                   machine=dict(cpu=_cpu_name(), cores=os.cpu_count(), python=platform.python_version(),
                                load_start=list(os.getloadavg())),
                   started=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), scenes={}, errors=[])
    images = {}
    references.code_fingerprint()  # the tracer code this run imports
    _section(results, "warming up (imports, kernels, spectral tables)")
    _warm_up(args.scenes)
    for name in args.scenes:
        _section(results, f"scene {name}")
        try:
            run_scene(name, cfg, results, images)
        except Exception as exc:  # a scene the renderer cannot do yet is reported, not fatal
            results["errors"].append(f"{name}: {type(exc).__name__}: {exc}")
            log(f"  {name} FAILED: {exc}")
    results["ceiling"] = []
    _section(results, "ceiling")
    for name in [n for n in args.scenes if n in results["scenes"]]:
        try:
            c = measure_ceiling(name, cfg)
            c["resolution"] = scene_config(cfg, name)["resolution"]
            results["ceiling"].append(c)
            log(f"ceiling {name}: {c['fraction']:.1%} ({c['samples_per_second']:.0f} vs "
                f"{c['ceiling_samples_per_second']:.0f} samples/s)")
        except Exception as exc:
            results["errors"].append(f"ceiling {name}: {type(exc).__name__}: {exc}")
    _section(results, "thread scaling")
    try:
        results["scaling"] = scaling.measure_scaling(quick=args.quick, log=log)
    except Exception as exc:
        results["errors"].append(f"thread scaling: {type(exc).__name__}: {exc}")
    results["stages"] = []
    for name in [n for n in args.scenes if n in results["scenes"]]:
        _section(results, f"stage split {name}")
        try:
            results["stages"].append(measure_stage_split(name, cfg))
        except Exception as exc:
            results["errors"].append(f"stage split {name}: {type(exc).__name__}: {exc}")
    _section(results, "cold compile and warm start (two fresh processes)")
    try:
        results["startup"] = st = startup.measure()
        log(f"  cold {st['cold']['process_seconds']:.1f} s, warm {st['warm']['process_seconds']:.1f} s")
    except Exception as exc:
        results["errors"].append(f"start-up: {type(exc).__name__}: {exc}")
    if not args.no_peers:
        for name in [n for n in args.scenes if n in results["scenes"] and scenes.SCENES[n].peers]:
            _section(results, f"peers on {name} ({', '.join(scenes.SCENES[name].peers)}) and Prism, interleaved")
            entry = results["scenes"][name]
            try:
                found, peer_images, equal_time, errors = run_peers(name, cfg, entry, images[(name, "cie")])
            except Exception as exc:
                results["errors"].append(f"peers on {name}: {type(exc).__name__}: {exc}")
                log(f"  FAILED: {exc}")
                continue
            for peer, error in errors.items():
                results["errors"].append(f"peer {peer} on {name}: {error}")
            for peer, result in found.items():
                entry.setdefault("peers", []).append(result)
                images[(name, peer)] = peer_images[peer]
                last = result["curve"][-1]
                log(f"  {peer}: {last['spp']} spp {last['seconds']:.2f} s relMSE {last['relmse']:.3g}")
            if equal_time is not None and found:
                entry["equal_time"] = equal_time
                last = equal_time["curve"][-1]
                log(f"  Prism: {last['spp']} spp {last['seconds']:.2f} s relMSE {last['relmse']:.3g}")
    if not args.no_demo:
        _section(results, "demo render (make render) now and before the compiled core")
        try:
            results["demo"] = d = demo.measure(results_dir, args.quick)
            if not args.quick:  # the README's picture is the image of the timed make render
                shutil.copyfile(results_dir / d["now"]["image"], references.REPO_ROOT / "docs" / "images" / "demo.png")
            before = d.get("before", {})
            log(f"  now {d['now']['process_seconds']:.1f} s, before "
                + (f"{before['process_seconds']:.1f} s" if "process_seconds" in before else before.get("error", "-")))
        except Exception as exc:
            results["errors"].append(f"demo: {type(exc).__name__}: {exc}")
    _section(results, "experiments")
    results["experiments"] = experiments.run_all(args.quick, log=log)
    results["machine"]["load_end"] = list(os.getloadavg())
    results["total_seconds"] = time.perf_counter() - started
    report.write_all(results, images, results_dir, docs)
    log(f"done in {results['total_seconds']:.0f} s; wrote {results_dir} and {docs}")
    return 0


def _warm_up(names):
    """Every kernel the scenes need loaded (or compiled) once, untimed: a tiny render of each scene
    with each of its strategies' settings."""
    for name in names:
        scene = scenes.build(name, (8, 8))
        for _, overrides in EXPERIMENTS[name]:
            threads = overrides.get("threads", THREADS)
            overrides = {k: v for k, v in overrides.items() if k != "threads"}
            progressive(scene, settings_for(overrides, 1, seed=0, threads=threads), [2])


def _cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


if __name__ == "__main__":
    sys.exit(main())
