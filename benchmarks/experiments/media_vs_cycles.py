"""Light inside things against Cycles at equal time: world fog and subsurface spheres, each rendered by Prism and
by Cycles 4.5 (CPU) from the same .blend scene, same threads and bounces.

Each renderer renders each sample count twice (seeds 0 and 1) in a bpy process of its own
(``_bpy_renders``); a render's relMSE comes from its two seeds (``metrics.relmse_from_two_seeds``: no
reference, so neither renderer is scored against the other's image). The equal-time ratio divides Prism's relMSE
by Cycles' at the same seconds, Cycles' curve interpolated in log-log: below 1, Prism is less noisy in the same
time. Where noise falls as 1/spp, relMSE x seconds is a constant of a renderer on a scene and the ratio of those
constants says the same; the fitted slope of log relMSE against log spp shows whether it does (rare bright
paths, such as fog scattering next to a point light, make it fall slower). The mean luminance of each (absolute
light, spp-weighted over all renders) shows that both render the same light.

``python -m benchmarks.experiments.media_vs_cycles [--quick]`` prints the rows and the summary.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

import numpy as np

from benchmarks.metrics import error_at_time, relmse_from_two_seeds
from benchmarks.references import REPO_ROOT

TITLE = "Light inside things: equal-time relMSE against Cycles (world fog, subsurface spheres)"
BOUNCES = 8
#: scene -> (full resolution, quick resolution); spp lists below
SCENES = {"fog": ((128, 96), (32, 24)), "subsurface": ((160, 80), (48, 24))}
FULL_SPP, QUICK_SPP = (16, 32, 64, 128), (4, 8)
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def renders(scene: str, resolution, spp, bounces: int = BOUNCES) -> dict:
    """``_bpy_renders``'s npz for ``scene`` (run in a subprocess: bpy stays out of this process)."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "renders.npz")
        command = [sys.executable, "-m", "benchmarks.experiments._bpy_renders", "--scene", scene, "--resolution",
                   *map(str, resolution), "--spp", *map(str, spp), "--bounces", str(bounces), "--out", out]
        proc = subprocess.run(command, cwd=REPO_ROOT, capture_output=True, text=True, timeout=1800)
        if proc.returncode != 0 or not os.path.exists(out):
            raise RuntimeError(f"_bpy_renders --scene {scene} failed ({proc.returncode}): {proc.stderr[-1500:]}")
        with np.load(out) as data:
            return {key: data[key] for key in data.files}


def _curves(data: dict) -> dict:
    """Per renderer: seconds (mean of the two seeds), relMSE and mean luminance per spp."""
    images, seconds = data["images"].astype(np.float64), data["seconds"]
    curves = {}
    for r, renderer in enumerate(data["renderers"]):
        curves[str(renderer)] = {
            "seconds": seconds[r].mean(axis=1),
            "relmse": np.array([relmse_from_two_seeds(pair[0], pair[1]) for pair in images[r]]),
            "luminance": (images[r] @ LUMINANCE).mean(axis=(1, 2, 3)),
        }
    return curves


def measure(data: dict) -> tuple[list[dict], dict]:
    """Rows per renderer and spp from one scene's renders, and the scene's figures: per renderer the median
    relMSE x seconds and seconds per spp over the counts above the smallest (where fixed costs weigh least), the
    spp-weighted mean luminance and the slope of log relMSE against log spp; ``equal_time``, the median over
    those counts of Prism's relMSE over Cycles' at Prism's seconds (Cycles' curve interpolated log-log,
    ``metrics.error_at_time``: no 1/t assumed); ``extrapolated``, whether a Prism time lay outside Cycles'."""
    spps = np.asarray(data["spp"])
    curves = _curves(data)
    cycles = curves["cycles"]
    first = 1 if len(spps) > 1 else 0
    rows, found = [], {"equal_time": [], "extrapolated": False}
    for renderer, curve in curves.items():
        for s, spp in enumerate(spps):
            time_s, error = float(curve["seconds"][s]), float(curve["relmse"][s])
            row = {"renderer": renderer, "spp": int(spp), "seconds": time_s, "relMSE": error,
                   "relMSE·s": error * time_s, "mean luminance": float(curve["luminance"][s])}
            if renderer == "prism":
                at_time, extrapolated = error_at_time(cycles["seconds"], cycles["relmse"], time_s)
                row["Cycles relMSE at these s"] = at_time
                row["Prism / Cycles at equal time"] = error / at_time
                if s >= first:
                    found["equal_time"].append(error / at_time)
                    found["extrapolated"] |= extrapolated
            rows.append(row)
        seconds, relmse = curve["seconds"][first:], curve["relmse"][first:]
        found[renderer] = {"relmse_s": float(np.median(relmse * seconds)),
                           "s_per_spp": float(np.median(seconds / spps[first:])),
                           "luminance": float(curve["luminance"] @ spps / spps.sum()),
                           "slope": float(np.polyfit(np.log(spps), np.log(curve["relmse"]), 1)[0])}
    found["equal_time"] = float(np.median(found["equal_time"]))
    return rows, found


def scene_sentence(scene: str, resolution, found: dict, target: float = 1.0) -> str:
    prism, cycles = found["prism"], found["cycles"]
    extended = " (Cycles' curve extended past its measured times)" if found["extrapolated"] else ""
    products = prism["relmse_s"] / cycles["relmse_s"]
    return (f"**{scene}** ({resolution[0]}x{resolution[1]}): Prism's relMSE at equal time is "
            f"**{found['equal_time']:.2f}x** Cycles'{extended} (target <= {target}); relMSE·s Prism "
            f"{prism['relmse_s']:.3g}, Cycles {cycles['relmse_s']:.3g} (ratio {products:.2f}); seconds per spp "
            f"Prism {prism['s_per_spp']:.3g}, Cycles {cycles['s_per_spp']:.3g}; mean luminance Prism "
            f"{prism['luminance']:.4g}, Cycles {cycles['luminance']:.4g} (Prism / Cycles "
            f"{prism['luminance'] / cycles['luminance']:.4f}); relMSE falls as spp^{prism['slope']:.2f} (Prism) and "
            f"spp^{cycles['slope']:.2f} (Cycles).")


def run(quick: bool) -> dict:
    spp = QUICK_SPP if quick else FULL_SPP
    rows, sentences, blender = [], [], ""
    for scene, resolutions in SCENES.items():
        resolution = resolutions[1] if quick else resolutions[0]
        data = renders(scene, resolution, spp)
        scene_rows, found = measure(data)
        rows += [{"scene": scene, **row} for row in scene_rows]
        sentences.append(scene_sentence(scene, resolution, found))
        blender = str(data["blender"])
    summary = (
        f"Prism and Cycles {blender} (CPU) render the same bpy scenes, 2 threads each, {BOUNCES} bounces, box "
        "filter, no adaptive sampling, denoising or clamping. fog: a grey floor in white world fog (Volume Scatter, "
        "0.15 /m) lit by a 400 W point light out of view (tests/helpers/fog_scenes.py); subsurface: a skin-like "
        "Principled sphere (Subsurface Weight 1, random walk) beside an orange Subsurface Scattering sphere (random "
        "walk, skin) under a sun and a grey world (tests/helpers/subsurface_scenes.py). Each renders "
        f"{', '.join(map(str, spp))} spp twice (seeds 0 and 1), the two renderers taking turns, every render timed "
        "whole through bpy (export or sync, sampling, EXR written and read) after an untimed warm-up. relMSE comes "
        "from the two seeds (no reference); the equal-time ratio is Prism's relMSE over Cycles' at Prism's seconds "
        "(Cycles' curve interpolated log-log), and it and relMSE·s are medians over the counts above the smallest. "
        + " ".join(sentences))
    return {"rows": rows, "summary": summary}


if __name__ == "__main__":
    from benchmarks.experiments import print_run

    print_run(run)
