"""Speed against error: ``python -m benchmarks.run [--quick] [--scenes a b ...]``.

For each scene: cached high-sample references, then for each strategy (the Sobol sampler's
counterpart with independent random numbers among them) a progressive render (median of ``repeats``
seeds) with wall time and relMSE / FLIP at each checkpoint; the embreex ceiling on the rays of one
pass; the time of a pass split by stage kernel; 1 -> 2 thread scaling next to embreex's on the same
rays; cold-compile and warm-start seconds; the peers (Mitsuba 3, Cycles) on the scenes they can render;
the demo render now and before the compiled core; the experiments of ``benchmarks/experiments/``.
Writes benchmarks/results/results.json, table.md, *.png and docs/performance.md.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from . import ceiling, demo, experiments, metrics, references, report, scenes, stage_split, startup
from .prism_runs import PASS_SPP, progressive, progressive_until, settings_for

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


def scene_config(cfg, name):
    """The run configuration with the scene's own overrides (resolution, spp)."""
    out = {k: v for k, v in cfg.items() if k != "per_scene"}
    out.update(cfg.get("per_scene", {}).get(name, {}))
    return out


GAUSS = {"wavelength_mode": "gaussian_rgb"}
INDEPENDENT_LABEL = "independent sampler"
INDEPENDENT = (INDEPENDENT_LABEL, {"sampler": "independent"})  # the sampler's gain: same spp, same reference
# (label, settings overrides); the first of each scene is its baseline (Sobol sampler).
EXPERIMENTS = {
    "cornell_grey": [
        ("default (cie x4, MIS, RR 3, 2 threads)", {}),
        ("1 thread", {"threads": 1}),
        ("no MIS (NEE only)", {"use_mis": False}),
        ("RR from bounce 1", {"russian_roulette_depth": 1}),
        ("no RR", {"russian_roulette_depth": 1000}),
        INDEPENDENT,
    ],
    "cornell_glass": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("cie x2", {"wavelengths_per_path": 2}),
        ("cie x8", {"wavelengths_per_path": 8}),
        ("gaussian_rgb", GAUSS),
        INDEPENDENT,
    ],
    "prism": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("cie x2", {"wavelengths_per_path": 2}),
        ("cie x8", {"wavelengths_per_path": 8}),
        ("gaussian_rgb", GAUSS),
        INDEPENDENT,
    ],
    "lens": [
        ("exit-pupil bounds (default)", {}),
        ("no pupil bounds", {"use_pupil_bounds": False}),
        INDEPENDENT,
    ],
    "soap_bubble": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("gaussian_rgb", GAUSS),
        INDEPENDENT,
    ],
    "mesh_1m": [
        ("default", {}),
        INDEPENDENT,
    ],
}
CEILING_SCENE = "cornell_glass"
THREADS = 2


def _reference_overrides(overrides: dict) -> dict:
    """gaussian_rgb converges to a different image (its channels are not CIE RGB):
    it gets its own reference; every other setting shares the default's."""
    return GAUSS if overrides.get("wavelength_mode") == "gaussian_rgb" else {}


def log(msg):
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", flush=True)


def _section(results, name):
    """Log the start of a part of the run with the machine's load average at that moment."""
    load = os.getloadavg()[0]
    results["machine"].setdefault("load_by_section", []).append([name, load])
    log(f"{name} (load {load:.1f})")


def curve_stats(runs, reference):
    """Per checkpoint medians over repeats: seconds, relMSE, FLIP."""
    out = []
    for k in range(len(runs[0])):
        points = [run[k] for run in runs]
        errs = [metrics.relmse(p["image"], reference["image"]) for p in points]
        flips = [metrics.flip(p["image"], reference["image"]) for p in points]
        out.append(dict(spp=points[0]["spp"], seconds=float(np.median([p["seconds"] for p in points])),
                        setup=float(np.median([p["setup"] for p in points])),
                        seconds_all=[float(p["seconds"]) for p in points],
                        relmse=float(np.median(errs)), flip=float(np.median(flips)),
                        relmse_all=[float(e) for e in errs],
                        rays=float(np.median([p["rays_cast"] for p in points]))))
    return out


def run_scene(name, cfg, results, images):
    cfg = scene_config(cfg, name)
    scene = scenes.build(name, (cfg["resolution"], cfg["resolution"]))
    entry = results["scenes"].setdefault(name, {"description": scenes.SCENES[name].description,
                                                "triangles": scene.triangle_count, "strategies": [],
                                                "resolution": cfg["resolution"], "checkpoints": cfg["checkpoints"]})
    refs = {}
    for label, overrides in EXPERIMENTS[name]:
        ref_over = _reference_overrides(overrides)
        ref_name = json.dumps(ref_over, sort_keys=True)
        if ref_name not in refs:
            refs[ref_name] = ref = references.prism_reference(name, scene, ref_over, cfg["ref_spp"],
                                                              cfg["ref_max_seconds"], THREADS, log=log)
            entry.setdefault("references", {})[ref_over.get("wavelength_mode", "cie")] = dict(
                spp=ref["spp"], seconds=ref["seconds"], cached=ref["cached"],
                noise_floor=metrics.relmse_noise_floor(ref["image"], ref["variance"]),
                negative_fraction=float((np.asarray(ref["image"]) < 0).any(axis=2).mean()))
            images[(name, ref_over.get("wavelength_mode", "cie"))] = ref["image"]
    # repeats outermost: a change in the machine's load falls on every strategy alike
    runs = {label: [] for label, _ in EXPERIMENTS[name]}
    strategies = {}
    for r in range(cfg["repeats"]):
        for label, overrides in EXPERIMENTS[name]:
            threads = overrides.get("threads", THREADS)
            settings = settings_for({k: v for k, v in overrides.items() if k != "threads"}, 1, seed=r, threads=threads)
            points, stats = progressive(scene, settings, cfg["checkpoints"])
            runs[label].append(points)
            strategies[label] = stats["strategy"]
    for label, overrides in EXPERIMENTS[name]:
        ref_over = _reference_overrides(overrides)
        curve = curve_stats(runs[label], refs[json.dumps(ref_over, sort_keys=True)])
        entry["strategies"].append(dict(label=label, overrides=overrides, strategy=strategies[label], curve=curve,
                                        reference=ref_over.get("wavelength_mode", "cie")))
        last = curve[-1]
        log(f"  {name} / {label}: {last['spp']} spp {last['seconds']:.2f} s relMSE {last['relmse']:.3g} "
            f"FLIP {last['flip']:.3f}")


def measure_ceiling(name, cfg):
    """Renderer pass time vs bare embreex on the same recorded rays, 2 threads."""
    cfg = scene_config(cfg, name)
    scene = scenes.build(name, (cfg["resolution"], cfg["resolution"]))
    settings = settings_for({}, samples=PASS_SPP * (cfg["ceiling_passes"] + 3), seed=7, threads=THREADS)
    from engine.tracer.renderer import Renderer

    renderer = Renderer(scene, settings)
    try:
        renderer.render_pass()  # warm-up
        rays_before = renderer.stats["rays_cast"]
        recorder = ceiling.record_pass(renderer)
        rays_counted = renderer.stats["rays_cast"] - rays_before
        replayer = ceiling.Replayer(renderer.geometry, recorder.batches, THREADS)
        # alternate renderer passes and embreex replays so load from other work hits both alike
        pass_times, embree_times, pass_cpu, embree_cpu = [], [], [], []
        for _ in range(cfg["ceiling_passes"]):
            t0, c0 = time.perf_counter(), time.process_time()
            renderer.render_pass()
            pass_times.append(time.perf_counter() - t0)
            pass_cpu.append(time.process_time() - c0)
            c0 = time.process_time()
            embree_times.append(replayer.seconds())
            embree_cpu.append(time.process_time() - c0)
        replayer.close()
    finally:
        renderer.close()
    pass_seconds = float(np.median(pass_times))
    embree_seconds = float(np.median(embree_times))
    samples = cfg["resolution"] ** 2 * PASS_SPP
    # CPU time of the process (all threads): what each side costs, whatever else runs on the machine
    cpu_fraction = float(np.median(embree_cpu)) / float(np.median(pass_cpu))
    return dict(scene=name, threads=THREADS, samples_per_pass=samples, pass_seconds=pass_seconds,
                embree_seconds=embree_seconds, fraction=embree_seconds / pass_seconds,
                pass_cpu_seconds=float(np.median(pass_cpu)), embree_cpu_seconds=float(np.median(embree_cpu)),
                cpu_fraction=cpu_fraction,
                pass_seconds_all=pass_times, embree_seconds_all=embree_times,
                rays_recorded=recorder.ray_count, closest_rays=recorder.count(ceiling.CLOSEST),
                film_rays=recorder.count(ceiling.BEFORE), shadow_rays=recorder.count(ceiling.OCCLUDED),
                rays_counted=int(rays_counted), batches=len(recorder.batches),
                samples_per_second=samples / pass_seconds, ceiling_samples_per_second=samples / embree_seconds,
                embree_rays_per_second=recorder.ray_count / embree_seconds)


def measure_thread_scaling(name, cfg):
    """Pass time with 1 and 2 threads against embreex replaying the same rays with 1
    and 2 threads, interleaved: how much of Embree's scaling the renderer keeps."""
    cfg = scene_config(cfg, name)
    scene = scenes.build(name, (cfg["resolution"], cfg["resolution"]))
    from engine.tracer.renderer import Renderer

    renderers = {t: Renderer(scene, settings_for({}, samples=10**6, seed=11, threads=t)) for t in (1, 2)}
    try:
        for r in renderers.values():
            r.render_pass()  # warm-up
        recorder = ceiling.record_pass(renderers[2])
        replayers = {t: ceiling.Replayer(renderers[2].geometry, recorder.batches, t) for t in (1, 2)}
        times = {(side, t): [] for side in ("prism", "embree") for t in (1, 2)}
        for _ in range(cfg["scaling_rounds"]):
            for t in (1, 2):
                t0 = time.perf_counter()
                renderers[t].render_pass()
                times[("prism", t)].append(time.perf_counter() - t0)
                times[("embree", t)].append(replayers[t].seconds())
        for rep in replayers.values():
            rep.close()
    finally:
        for r in renderers.values():
            r.close()
    med = {k: float(np.median(v)) for k, v in times.items()}
    prism_speedup, embree_speedup = med[("prism", 1)] / med[("prism", 2)], med[("embree", 1)] / med[("embree", 2)]
    return dict(scene=name, rounds=cfg["scaling_rounds"], rays=recorder.ray_count,
                prism_1=med[("prism", 1)], prism_2=med[("prism", 2)], embree_1=med[("embree", 1)],
                embree_2=med[("embree", 2)], prism_speedup=prism_speedup, embree_speedup=embree_speedup,
                kept=prism_speedup / embree_speedup, all={f"{k[0]}_{k[1]}": v for k, v in times.items()})


def measure_stage_split(name, cfg):
    """A pass's time split by stage with 1 and with 2 threads (passes wrapped, not the timed ones)."""
    cfg = scene_config(cfg, name)
    scene = scenes.build(name, (cfg["resolution"], cfg["resolution"]))
    return dict(scene=name, resolution=cfg["resolution"],
                **{str(t): stage_split.stage_split(scene, {}, t, passes=cfg["ceiling_passes"]) for t in (1, 2)})


def _peer_round(peer, name, cfg, first_repeat, reference_key):
    """One peer process rendering repeat ``first_repeat`` of its sweep (and its reference when
    ``reference_key`` is given); returns the loaded output and the process's wall time."""
    res = cfg["resolution"]
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "peer.npz")
        cmd = [sys.executable, "-m", f"benchmarks.peers.{peer}", "--scene", name, "--resolution", str(res),
               "--threads", str(THREADS), "--repeats", "1", "--first-repeat", str(first_repeat), "--out", out,
               "--spp", *[str(s) for s in cfg["peer_spp"][peer]]]
        if reference_key is not None:
            cmd += ["--reference-spp", str(cfg["peer_ref_spp"][peer]), "--reference-chunks", "8"]
        start = time.perf_counter()
        proc = subprocess.run(cmd, cwd=references.REPO_ROOT, capture_output=True, text=True, timeout=1500)
        if proc.returncode != 0 or not os.path.exists(out):
            raise RuntimeError(f"{peer} failed ({proc.returncode}): {proc.stderr[-2000:]}")
        from .peers.common import load

        data = load(out)
    if reference_key is not None:
        references.store(reference_key, data["reference"], data["reference_variance"], int(data["reference_spp"]),
                         float(data["reference_seconds"]))
    return data, time.perf_counter() - start


def _peer_result(peer, rounds, ref, prism_ref, wall):
    """A peer's curve (medians over its rounds) against its own reference."""
    seconds = np.concatenate([d["seconds"] for d in rounds])
    images = np.concatenate([d["images"] for d in rounds])
    curve = []
    for k, spp in enumerate(rounds[0]["spp"]):
        errs = [metrics.relmse(images[r, k], ref["image"]) for r in range(len(images))]
        flips = [metrics.flip(images[r, k], ref["image"]) for r in range(len(images))]
        curve.append(dict(spp=int(spp), seconds=float(np.median(seconds[:, k])),
                          relmse=float(np.median(errs)), flip=float(np.median(flips)),
                          relmse_all=[float(e) for e in errs], seconds_all=[float(t) for t in seconds[:, k]]))
    ratio = ref["image"] / np.maximum(prism_ref, 1e-6)
    lit = prism_ref > 0.05 * prism_ref.mean()
    return dict(peer=peer, info=rounds[0]["info"], curve=curve, wall_seconds=wall,
                reference=dict(spp=ref["spp"], seconds=ref["seconds"], cached=ref.get("cached", False),
                               noise_floor=metrics.relmse_noise_floor(ref["image"], ref["variance"]),
                               negative_fraction=float((np.asarray(ref["image"]) < 0).any(axis=2).mean())),
                convention_ratio_median=float(np.median(ratio[lit])),
                convention_ratio_of_means=float(ref["image"].mean() / prism_ref.mean()))


def run_peers(name, cfg, entry, prism_ref, log=log):
    """The peers of scene ``name`` and Prism's equal-time curve, interleaved repeat by repeat (peer A
    repeat r, peer B repeat r, Prism repeat r, ...) so that a change in the machine's load falls on
    every side. Prism's default settings render until they have taken as long as the slowest peer's
    longest render of the first round (spp doubling from the first checkpoint, at most 1/8 of the
    reference's spp; later repeats use the same checkpoints), so both curves cover the time at which
    they are compared. Returns ({peer: result}, {peer: reference image}, equal-time curve or None,
    {peer: error})."""
    cfg = scene_config(cfg, name)
    peers = list(scenes.SCENES[name].peers)
    keys = {p: references.peer_reference_key(p, name, cfg["resolution"], cfg["peer_ref_spp"][p], p) for p in peers}
    refs = {p: references.load(keys[p]) for p in peers}
    rounds = {p: [] for p in peers}
    walls = {p: 0.0 for p in peers}
    errors = {}
    scene = scenes.build(name, (cfg["resolution"], cfg["resolution"]))
    max_spp = max(cfg["checkpoints"][-1], entry["references"]["cie"]["spp"] // 8)
    prism_runs, checkpoints, target = [], None, None
    for r in range(cfg["repeats"]):
        for peer in [p for p in peers if p not in errors]:
            log(f"  {peer} repeat {r + 1}/{cfg['repeats']}" + (" + reference" if refs[peer] is None else ""))
            try:
                data, wall = _peer_round(peer, name, cfg, r, keys[peer] if refs[peer] is None else None)
            except Exception as exc:
                errors[peer] = f"{type(exc).__name__}: {exc}"
                log(f"  FAILED: {exc}")
                continue
            if refs[peer] is None:
                refs[peer] = references.load(keys[peer])
            rounds[peer].append(data)
            walls[peer] += wall
        done = [p for p in peers if rounds[p]]
        if not done:
            break
        if target is None:
            target = max(float(rounds[p][0]["seconds"].max()) for p in done)
            points, _ = progressive_until(scene, settings_for({}, 1, seed=0, threads=THREADS), cfg["checkpoints"][0],
                                          target, max_spp)
            checkpoints = [p["spp"] for p in points]
        else:
            points, _ = progressive(scene, settings_for({}, 1, seed=r, threads=THREADS), checkpoints)
        prism_runs.append(points)
    found = {p: _peer_result(p, rounds[p], refs[p], prism_ref, walls[p]) for p in peers if rounds[p]}
    images = {p: refs[p]["image"] for p in found}
    equal_time = None
    if prism_runs:
        equal_time = dict(curve=curve_stats(prism_runs, {"image": prism_ref}), target_seconds=target,
                          max_spp=max_spp)
    return found, images, equal_time, errors


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
    if CEILING_SCENE in results["scenes"]:
        _section(results, "thread scaling")
        try:
            results["thread_scaling"] = ts = measure_thread_scaling(CEILING_SCENE, cfg)
            log(f"threads 1 -> 2 on {CEILING_SCENE}: Prism x{ts['prism_speedup']:.2f}, "
                f"embreex x{ts['embree_speedup']:.2f}")
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
