"""What ``python -m benchmarks.run`` measures, scene by scene: the strategies of each scene (``EXPERIMENTS``)
rendered progressively against cached references, the embreex ceiling on the rays of one pass, 1 -> 2
thread scaling next to embreex's on the same rays, a pass's time split by stage, and the peers' rounds
(Mitsuba 3, Cycles) interleaved with Prism's equal-time curve. Each function returns (or fills in) the
plain-data records that ``run.main`` collects into results.json.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from . import ceiling, metrics, references, scenes, stage_split
from .prism_runs import PASS_SPP, progressive, progressive_until, settings_for


def scene_config(cfg, name):
    """The run configuration with the scene's own overrides (resolution, spp)."""
    out = {k: v for k, v in cfg.items() if k != "per_scene"}
    out.update(cfg.get("per_scene", {}).get(name, {}))
    return out


GAUSS = {"wavelength_mode": "gaussian_rgb"}
INDEPENDENT_LABEL = "independent sampler"
INDEPENDENT = (INDEPENDENT_LABEL, {"sampler": "independent"})  # the sampler's gain: same spp, same reference
#: Dispersive scenes: wavelengths per path, and the per-channel Gaussians of the student renderer.
WAVELENGTH_STRATEGIES = [
    ("cie x4 (default)", {}),
    ("cie x1", {"wavelengths_per_path": 1}),
    ("cie x2", {"wavelengths_per_path": 2}),
    ("cie x8", {"wavelengths_per_path": 8}),
    ("gaussian_rgb", GAUSS),
    INDEPENDENT,
]
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
    "cornell_glass": WAVELENGTH_STRATEGIES,
    "prism": WAVELENGTH_STRATEGIES,
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
    settings = settings_for({}, samples=PASS_SPP * (cfg["ceiling_passes"] + 3), seed=7, threads=THREADS)
    from engine.tracer.renderer import Renderer

    renderer = Renderer(scene, settings)
    try:
        renderer.render_pass()  # warm-up
        rays_before = renderer.stats["rays_cast"]
        recorder = ceiling.record_pass(renderer)
        rays_counted = renderer.stats["rays_cast"] - rays_before
        replayer = ceiling.Replayer(renderer.tables.geometry, recorder.batches, THREADS)
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
