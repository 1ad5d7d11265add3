"""The demo render (``make render``) now and before the compiled core, timed in the same run.

Both sides run exactly what ``make render`` runs, each from its own source tree: this checkout, and
the tree of ``BEFORE_COMMIT`` (the numpy tracer, the last commit before the compiled core) exported
with ``git archive`` into a temporary folder. Each tree builds the demo scene with its own
``demo/build_demo_scene.py`` (the same scene script in both) and renders it with its own
``render.py --samples 64`` (480 x 320, all cores) in a fresh process, twice (seeds 0 and 1, the trees
taking turns), after one untimed 1-spp render of the same scene (imports from disk, kernels compiled
into the harness's kernel cache, so the timed render is a user's second ``make render``). matplotlib is hidden from these processes, as it is absent
from the project's venv and from Blender. Reported: the process's wall time (bpy start-up, scene load,
export, render, PNG) and Blender's own ``Time:`` line (the render job), each the mean of the two seeds;
the noise of each tree's image (``display_noise``: what two seeds disagree on, in display levels); the
images; and the demo scene's pass split by stage (``tools/profile_pass.py --blend``).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .references import CACHE_DIR, REPO_ROOT

BEFORE_COMMIT = "8fdab610b5d103e736e24abd3dc9abee44c279c1"
FULL_SPP, QUICK_SPP = 64, 4
_BLENDER_TIME = re.compile(r"Time: (\d+):(\d+(?:\.\d+)?)")


def _export_tree(commit: str, folder: Path) -> None:
    archive = subprocess.run(["git", "archive", "--format=tar", commit], cwd=REPO_ROOT, capture_output=True,
                             check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True, capture_output=True)


# Runs a script as ``python script args`` would, with matplotlib hidden: the project's venv
# (requirements.txt) and Blender have none, but ``make bench`` installs it, and colour-science then
# imports matplotlib.pyplot (about a second) in every render process.
_WITHOUT_MATPLOTLIB = ("import runpy, sys; sys.modules['matplotlib'] = None; sys.argv = sys.argv[1:]; "
                       "sys.path.insert(0, '.'); runpy.run_path(sys.argv[0], run_name='__main__')")


def _run(tree: Path, args, env, timeout=1800) -> tuple[float, str]:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _WITHOUT_MATPLOTLIB, *args], cwd=tree, env=env, capture_output=True,
                          text=True, timeout=timeout)
    seconds = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args[:2])} in {tree} failed ({proc.returncode}): {proc.stderr[-1500:]}")
    return seconds, proc.stdout + proc.stderr


def _blender_seconds(output: str) -> float:
    found = _BLENDER_TIME.findall(output)
    return float("nan") if not found else 60 * int(found[-1][0]) + float(found[-1][1])


def _prepare(tree: Path, work: Path, env) -> Path:
    blend = work / "demo.blend"
    _run(tree, ["demo/build_demo_scene.py", str(blend)], env)
    _run(tree, ["render.py", str(blend), "--samples", "1", "--output", str(work / "warm.png")], env)
    return blend


def _timed(tree: Path, blend: Path, spp: int, image: Path, seed: int, env) -> dict:
    seconds, output = _run(tree, ["render.py", str(blend), "--samples", str(spp), "--seed", str(seed),
                                  "--output", str(image)], env)
    return dict(process_seconds=seconds, blender_seconds=_blender_seconds(output), image=str(image))


def display_noise(first: Path, second: Path) -> float:
    """Noise of one image in 8-bit display levels: the RMS difference of two renders with different
    seeds (as PNGs, through the scene's view transform, as a user sees them) divided by sqrt(2)."""
    import imageio.v3 as iio
    import numpy as np

    a = iio.imread(first)[..., :3].astype(np.float64)
    b = iio.imread(second)[..., :3].astype(np.float64)
    return float(np.sqrt(np.mean((a - b) ** 2) / 2.0))


def _mean(runs, key):
    return sum(r[key] for r in runs) / len(runs)


def _profile(blend: Path, path: Path, env) -> dict:
    """The demo scene's pass split by stage and against the embreex ceiling (``tools/profile_pass.py
    --blend``, 4-spp passes, 2 threads), or ``{"error": ...}``."""
    try:
        _run(REPO_ROOT, ["tools/profile_pass.py", "--blend", str(blend), "--spp", "4", "--passes", "3",
                         "--json", str(path)], env)
        return json.loads(path.read_text())
    except (RuntimeError, OSError, ValueError) as exc:
        return dict(error=f"{type(exc).__name__}: {str(exc)[-300:]}")


def measure(results_dir: Path, quick: bool) -> dict:
    """Time the demo render of this tree and of ``BEFORE_COMMIT``'s; images go to ``results_dir``
    (``demo.png``, ``demo_before.png``). ``before`` holds an ``error`` when that tree is not available
    (no git history, e.g. an exported copy)."""
    spp = QUICK_SPP if quick else FULL_SPP
    results_dir.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, PRISM_KERNEL_CACHE=str(CACHE_DIR / "kernels"))  # kept between runs
    env.pop("NUMBA_CACHE_DIR", None)
    out = dict(spp=spp, resolution=[480, 320], before_commit=BEFORE_COMMIT, load_start=list(os.getloadavg()))
    with tempfile.TemporaryDirectory(prefix="prism-demo-") as tmp:
        tmp = Path(tmp)
        (tmp / "now").mkdir()
        now_blend = _prepare(REPO_ROOT, tmp / "now", env)
        before_tree = tmp / "before_tree"
        before_blend = None
        try:
            before_tree.mkdir()
            _export_tree(BEFORE_COMMIT, before_tree)
            (tmp / "before").mkdir()
            before_blend = _prepare(before_tree, tmp / "before", env)
        except (subprocess.CalledProcessError, RuntimeError, OSError) as exc:
            out["before"] = dict(error=f"{type(exc).__name__}: {str(exc)[-300:]}")
        # interleaved: now, before, now, before (seeds 0, 0, 1, 1) -- a change in the machine's load falls
        # on both, and each tree's two seeds measure its noise
        runs = {"now": [], "before": []}
        trees = [("now", REPO_ROOT, now_blend)] + ([("before", before_tree, before_blend)] if before_blend else [])
        for seed in (0, 1):
            for side, tree, blend in trees:
                runs[side].append(_timed(tree, blend, spp, tmp / side / f"demo_{seed}.png", seed, env))
        for side, _, _ in trees:
            name = "demo.png" if side == "now" else "demo_before.png"
            shutil.copyfile(runs[side][0]["image"], results_dir / name)
            out[side] = dict(process_seconds=_mean(runs[side], "process_seconds"),
                             blender_seconds=_mean(runs[side], "blender_seconds"),
                             runs=[r["process_seconds"] for r in runs[side]], image=name,
                             noise=display_noise(runs[side][0]["image"], runs[side][1]["image"]))
        out["profile"] = _profile(now_blend, tmp / "profile.json", env)
    out["load_end"] = list(os.getloadavg())
    if "process_seconds" in out.get("before", {}):
        out["speedup_process"] = out["before"]["process_seconds"] / out["now"]["process_seconds"]
        out["speedup_blender"] = out["before"]["blender_seconds"] / out["now"]["blender_seconds"]
        out["noise_ratio"] = out["before"]["noise"] / out["now"]["noise"]
    return out
