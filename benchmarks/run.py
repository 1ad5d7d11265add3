"""Speed against error: ``python -m benchmarks.run [--quick] [--scenes a b ...]``.

For each scene: cached high-sample references, then for each strategy a
progressive render (median of ``repeats`` seeds) with wall time and relMSE /
FLIP at each checkpoint; the embreex ceiling on the rays of one pass; a cProfile
summary of a pass; the peers (Mitsuba 3, Cycles) on the scenes they can render.
Writes benchmarks/results/results.json, table.md, *.png and docs/performance.md.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from . import ceiling, metrics, references, report, scenes
from .prism_runs import PASS_SPP, profile_pass, progressive, settings_for

RESULTS_DIR = references.BENCH_DIR / "results"

FULL = dict(resolution=64, checkpoints=[4, 8, 16, 32], repeats=3, ref_spp=512, ref_max_seconds=120.0,
            peer_spp={"mitsuba": [4, 8, 16, 32, 64, 128, 256, 512], "cycles": [4, 8, 16, 32, 64, 128]},
            peer_ref_spp={"mitsuba": 8192, "cycles": 1024}, ceiling_passes=3,
            per_scene={"prism": dict(resolution=32, checkpoints=[16, 32, 64, 128, 256, 512], ref_spp=4096,
                                     ref_max_seconds=150.0),
                       "mesh_1m": dict(peer_spp={"mitsuba": [4, 8, 16, 32, 64, 128, 256, 512]},
                                       peer_ref_spp={"mitsuba": 2048})})
QUICK = dict(resolution=32, checkpoints=[2, 4, 8, 16], repeats=2, ref_spp=256, ref_max_seconds=30.0,
             peer_spp={"mitsuba": [2, 4, 8, 16, 32, 64], "cycles": [2, 4, 8, 16, 32, 64]},
             peer_ref_spp={"mitsuba": 2048, "cycles": 512}, ceiling_passes=2,
             per_scene={"prism": dict(resolution=24, checkpoints=[8, 16, 32, 64, 128], ref_spp=1024,
                                      ref_max_seconds=40.0)})


def scene_config(cfg, name):
    """The run configuration with the scene's own overrides (resolution, spp)."""
    out = {k: v for k, v in cfg.items() if k != "per_scene"}
    out.update(cfg.get("per_scene", {}).get(name, {}))
    return out


GAUSS = {"wavelength_mode": "gaussian_rgb"}
# (label, settings overrides); the first of each scene is its baseline.
EXPERIMENTS = {
    "cornell_grey": [
        ("default (cie x4, MIS, RR 3, 2 threads)", {}),
        ("1 thread", {"threads": 1}),
        ("no MIS (NEE only)", {"use_mis": False}),
        ("RR from bounce 1", {"russian_roulette_depth": 1}),
        ("no RR", {"russian_roulette_depth": 1000}),
    ],
    "cornell_glass": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("cie x2", {"wavelengths_per_path": 2}),
        ("cie x8", {"wavelengths_per_path": 8}),
        ("gaussian_rgb", GAUSS),
    ],
    "prism": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("cie x2", {"wavelengths_per_path": 2}),
        ("cie x8", {"wavelengths_per_path": 8}),
        ("gaussian_rgb", GAUSS),
    ],
    "lens": [
        ("exit-pupil bounds (default)", {}),
        ("no pupil bounds", {"use_pupil_bounds": False}),
    ],
    "soap_bubble": [
        ("cie x4 (default)", {}),
        ("cie x1", {"wavelengths_per_path": 1}),
        ("gaussian_rgb", GAUSS),
    ],
    "mesh_1m": [
        ("default", {}),
    ],
}
CEILING_SCENE = "cornell_glass"
PROFILE_SCENE = "cornell_glass"
THREADS = 2


def _reference_overrides(overrides: dict) -> dict:
    """gaussian_rgb converges to a different image (its channels are not CIE RGB):
    it gets its own reference; every other setting shares the default's."""
    return GAUSS if overrides.get("wavelength_mode") == "gaussian_rgb" else {}


def log(msg):
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", flush=True)


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
    settings = settings_for({}, samples=PASS_SPP * (cfg["ceiling_passes"] + 2), seed=7, threads=THREADS)
    from engine.tracer.renderer import Renderer

    renderer = Renderer(scene, settings)
    try:
        accel = ceiling.find_accel(renderer)
        if accel is None:
            raise RuntimeError("renderer has no accel object with intersect/occluded")
        recorder = ceiling.RayRecorder(accel)
        renderer.render_pass()  # warm-up
        rays_before = renderer.stats["rays_cast"]
        recorder.active = True
        renderer.render_pass()
        recorder.active = False
        recorder.uninstall()
        rays_counted = renderer.stats["rays_cast"] - rays_before
        replayer = ceiling.Replayer(scene.vertices, scene.triangles, recorder.batches, THREADS)
        # alternate renderer passes and embreex replays so load from other work hits both alike
        pass_times, embree_times = [], []
        for _ in range(cfg["ceiling_passes"]):
            t0 = time.perf_counter()
            renderer.render_pass()
            pass_times.append(time.perf_counter() - t0)
            embree_times.append(replayer.seconds())
        replayer.close()
    finally:
        renderer.close()
    pass_seconds = float(np.median(pass_times))
    embree_seconds = float(np.median(embree_times))
    samples = cfg["resolution"] ** 2 * PASS_SPP
    closest = sum(len(b[1]) for b in recorder.batches if b[0] == "closest")
    return dict(scene=name, threads=THREADS, samples_per_pass=samples, pass_seconds=pass_seconds,
                embree_seconds=embree_seconds, fraction=embree_seconds / pass_seconds,
                rays_recorded=recorder.ray_count, closest_rays=closest, rays_counted=int(rays_counted),
                batches=len(recorder.batches),
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
        recorder = ceiling.RayRecorder(ceiling.find_accel(renderers[2]))
        for r in renderers.values():
            r.render_pass()  # warm-up
        recorder.active = True
        renderers[2].render_pass()
        recorder.active = False
        recorder.uninstall()
        replayers = {t: ceiling.Replayer(scene.vertices, scene.triangles, recorder.batches, t) for t in (1, 2)}
        times = {("prism", t): [] for t in (1, 2)}
        times.update({("embree", t): [] for t in (1, 2)})
        for _ in range(cfg["ceiling_passes"]):
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
    return dict(scene=name, prism_1=med[("prism", 1)], prism_2=med[("prism", 2)], embree_1=med[("embree", 1)],
                embree_2=med[("embree", 2)], prism_speedup=med[("prism", 1)] / med[("prism", 2)],
                embree_speedup=med[("embree", 1)] / med[("embree", 2)])


def run_peer(peer, name, cfg, prism_entry):
    """Run a peer in its own process; return its curve against its own reference."""
    cfg = scene_config(cfg, name)
    res = cfg["resolution"]
    version = {"mitsuba": "mitsuba", "cycles": "cycles"}[peer]
    key = references.peer_reference_key(peer, name, res, cfg["peer_ref_spp"][peer], version)
    cached = references.load(key)
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "peer.npz")
        cmd = [sys.executable, "-m", f"benchmarks.peers.{peer}", "--scene", name, "--resolution", str(res),
               "--threads", str(THREADS), "--repeats", str(cfg["repeats"]), "--out", out,
               "--spp", *[str(s) for s in cfg["peer_spp"][peer]]]
        if cached is None:
            cmd += ["--reference-spp", str(cfg["peer_ref_spp"][peer]), "--reference-chunks", "8"]
        start = time.perf_counter()
        proc = subprocess.run(cmd, cwd=references.REPO_ROOT, capture_output=True, text=True, timeout=1500)
        if proc.returncode != 0 or not os.path.exists(out):
            raise RuntimeError(f"{peer} failed ({proc.returncode}): {proc.stderr[-2000:]}")
        from .peers.common import load

        data = load(out)
    if cached is None:
        cached = references.store(key, data["reference"], data["reference_variance"], int(data["reference_spp"]),
                                  float(data["reference_seconds"]))
    ref = cached
    curve = []
    for k, spp in enumerate(data["spp"]):
        errs = [metrics.relmse(data["images"][r, k], ref["image"]) for r in range(len(data["images"]))]
        flips = [metrics.flip(data["images"][r, k], ref["image"]) for r in range(len(data["images"]))]
        curve.append(dict(spp=int(spp), seconds=float(np.median(data["seconds"][:, k])),
                          relmse=float(np.median(errs)), flip=float(np.median(flips)),
                          relmse_all=[float(e) for e in errs],
                          seconds_all=[float(t) for t in data["seconds"][:, k]]))
    prism_ref = prism_entry["_ref_image"]
    ratio = ref["image"] / np.maximum(prism_ref, 1e-6)
    lit = prism_ref > 0.05 * prism_ref.mean()
    return dict(peer=peer, info=data["info"], curve=curve, wall_seconds=time.perf_counter() - start,
                reference=dict(spp=ref["spp"], seconds=ref["seconds"], cached=ref.get("cached", False),
                               noise_floor=metrics.relmse_noise_floor(ref["image"], ref["variance"]),
                negative_fraction=float((np.asarray(ref["image"]) < 0).any(axis=2).mean())),
                convention_ratio_median=float(np.median(ratio[lit])),
                convention_ratio_of_means=float(ref["image"].mean() / prism_ref.mean())), ref["image"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="32x32, fewer samples and repeats")
    parser.add_argument("--scenes", nargs="*", default=list(EXPERIMENTS), choices=list(EXPERIMENTS))
    parser.add_argument("--no-peers", action="store_true")
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
    log("warming up (imports, spectral tables)")
    _warm_up(cfg)
    for name in args.scenes:
        log(f"scene {name}")
        try:
            run_scene(name, cfg, results, images)
        except Exception as exc:  # a scene the renderer cannot do yet is reported, not fatal
            results["errors"].append(f"{name}: {type(exc).__name__}: {exc}")
            log(f"  {name} FAILED: {exc}")
    results["ceiling"] = []
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
        try:
            results["thread_scaling"] = ts = measure_thread_scaling(CEILING_SCENE, cfg)
            log(f"threads 1 -> 2 on {CEILING_SCENE}: Prism x{ts['prism_speedup']:.2f}, "
                f"embreex x{ts['embree_speedup']:.2f}")
        except Exception as exc:
            results["errors"].append(f"thread scaling: {type(exc).__name__}: {exc}")
    if PROFILE_SCENE in results["scenes"]:
        log("profiling a pass")
        res = scene_config(cfg, PROFILE_SCENE)["resolution"]
        try:
            results["profile"] = dict(scene=PROFILE_SCENE, resolution=res,
                                      **profile_pass(scenes.build(PROFILE_SCENE, (res, res)), {}))
        except Exception as exc:
            results["errors"].append(f"profile: {type(exc).__name__}: {exc}")
    if not args.no_peers:
        for name in [n for n in args.scenes if n in results["scenes"]]:
            for peer in scenes.SCENES[name].peers:
                log(f"peer {peer} on {name}")
                try:
                    results["scenes"][name]["_ref_image"] = images[(name, "cie")]
                    peer_result, peer_image = run_peer(peer, name, cfg, results["scenes"][name])
                    results["scenes"][name].setdefault("peers", []).append(peer_result)
                    images[(name, peer)] = peer_image
                    last = peer_result["curve"][-1]
                    log(f"  {peer}: {last['spp']} spp {last['seconds']:.2f} s relMSE {last['relmse']:.3g}")
                except Exception as exc:
                    results["errors"].append(f"peer {peer} on {name}: {type(exc).__name__}: {exc}")
                    log(f"  FAILED: {exc}")
                finally:
                    results["scenes"][name].pop("_ref_image", None)
    results["machine"]["load_end"] = list(os.getloadavg())
    results["total_seconds"] = time.perf_counter() - started
    report.write_all(results, images, results_dir, docs)
    log(f"done in {results['total_seconds']:.0f} s; wrote {results_dir} and {docs}")
    return 0


def _warm_up(cfg):
    scene = scenes.build("cornell_grey", (16, 16))
    progressive(scene, settings_for({}, 1, seed=0, threads=THREADS), [2])
    progressive(scene, settings_for(GAUSS, 1, seed=0, threads=THREADS), [2])


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
