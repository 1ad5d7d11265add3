"""Cold-compile and warm-start seconds of the compiled tracer.

``measure()`` runs ``python -m benchmarks.startup --child`` twice in fresh processes with
``PRISM_KERNEL_CACHE`` pointing at a new empty folder: the first run (cold) imports the tracer,
compiles every kernel a small render needs and renders it; the second (warm) does the same with the
kernels now on disk. Each child reports its phases (import of the tracer, scene set-up, first pass,
second pass), whether ``jit.cache_is_warm()`` said so (the flag behind "Compiling Prism kernels (first render
only)") and whether the render imported colour-science (it should not: half a second, and its tables
ship with Prism, ``spectra.colorimetry_tables``; matplotlib is hidden as in Blender, which lacks it);
the parent adds the whole process's wall time (interpreter start-up included). A cold child also splits
its compile (``compile_events``): seconds in numba's front end and in LLVM, and how many functions compiled.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

from .compile_events import CompileRecorder
from .references import REPO_ROOT

SCENE = "cornell_glass"  # diffuse + dielectric, area light: the kernels of most renders
RESOLUTION = 16


def _child() -> int:
    # As inside Blender, which ships no matplotlib: colour-science imports matplotlib.pyplot (about a
    # second) whenever it is installed, as it is in the benchmark's environment.
    sys.modules["matplotlib"] = None
    start = time.perf_counter()
    from engine.tracer import jit
    from engine.tracer.renderer import Renderer
    from engine.tracer.stages import trace  # noqa: F401 - every stage kernel module
    from engine.tracer.settings import RenderSettings

    imported = time.perf_counter()
    compiles = CompileRecorder().install()
    warm = jit.cache_is_warm()
    from benchmarks import scenes

    scene = scenes.build(SCENE, (RESOLUTION, RESOLUTION))
    built = time.perf_counter()
    with Renderer(scene, RenderSettings(samples=2, samples_per_pass=1, seed=0, threads=2)) as renderer:
        constructed = time.perf_counter()
        renderer.render_pass()
        first = time.perf_counter()
        renderer.render_pass()
        second = time.perf_counter()
    jit.mark_cache_warm()
    print(json.dumps(dict(import_seconds=imported - start, scene_seconds=built - imported,
                          setup_seconds=constructed - built, first_pass_seconds=first - constructed,
                          second_pass_seconds=second - first, render_seconds=second - start,
                          cache_was_warm=warm, **compiles.summary(),
                          colour_imported=any(name.split(".")[0] == "colour" for name in sys.modules))))
    return 0


def _run_child(cache: str) -> dict:
    env = dict(os.environ, PRISM_KERNEL_CACHE=cache)
    env.pop("NUMBA_CACHE_DIR", None)
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "benchmarks.startup", "--child"], cwd=REPO_ROOT, env=env,
                          capture_output=True, text=True, timeout=900)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"startup child failed ({proc.returncode}): {proc.stderr[-2000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["process_seconds"] = wall
    return out


def measure() -> dict:
    """{"cold": {...}, "warm": {...}, "scene", "resolution"}: phases in seconds of a fresh process
    rendering ``SCENE`` at ``RESOLUTION``^2 (2 passes of 1 spp) with an empty, then a filled cache."""
    with tempfile.TemporaryDirectory(prefix="prism-kernels-") as cache:
        cold = _run_child(cache)
        warm = _run_child(cache)
    return dict(scene=SCENE, resolution=RESOLUTION, cold=cold, warm=warm)


if __name__ == "__main__":
    if "--child" in sys.argv:
        sys.exit(_child())
    print(json.dumps(measure(), indent=1))
