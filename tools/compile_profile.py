"""Where a cold compile of the tracer's kernels goes, function by function.

    .venv/bin/python tools/compile_profile.py [SCENE] [--top 25] [--json FILE]

Renders a benchmark scene (``benchmarks/scenes.py``, default cornell_glass, as ``benchmarks.startup``)
at 16 x 16 in a fresh process whose kernel cache is an empty temporary folder, and prints what numba
compiled (``benchmarks.compile_events``): per function its signatures and self seconds (its callees'
compiles taken out; the bodies of ``jit.inlined`` functions count in their callers, once per call site),
and the split between numba's front end and LLVM. A cold compile takes minutes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def _child(scene_name: str, out: str) -> None:
    sys.modules["matplotlib"] = None  # as in Blender; colour-science would import it
    from benchmarks import scenes
    from benchmarks.compile_events import CompileRecorder
    from engine.tracer.renderer import Renderer
    from engine.tracer.settings import RenderSettings

    recorder = CompileRecorder().install()
    scene = scenes.build(scene_name, (16, 16))
    start = time.perf_counter()
    with Renderer(scene, RenderSettings(samples=1, samples_per_pass=1, seed=0, threads=1)) as renderer:
        renderer.render_pass()
    result = dict(scene=scene_name, seconds=time.perf_counter() - start, **recorder.summary(),
                  functions=[dict(function=f, signatures=n, self_seconds=own, inclusive_seconds=inclusive)
                             for f, n, own, inclusive in recorder.by_function()])
    Path(out).write_text(json.dumps(result), encoding="utf-8")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default="cornell_glass")
    parser.add_argument("--top", type=int, default=25)
    parser.add_argument("--json", help="also write the figures to this file")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(args.scene, args.child)
        return 0
    with tempfile.TemporaryDirectory(prefix="prism-compile-") as folder:
        out = os.path.join(folder, "profile.json")
        env = dict(os.environ, PRISM_KERNEL_CACHE=os.path.join(folder, "kernels"))
        env.pop("NUMBA_CACHE_DIR", None)
        subprocess.run([sys.executable, __file__, args.scene, "--child", out], env=env, check=True, cwd=ROOT)
        result = json.loads(Path(out).read_text(encoding="utf-8"))
    front = result["compile_seconds"] - result["llvm_seconds"]
    print(f"{result['scene']}: first pass {result['seconds']:.1f} s; compiling {result['compile_seconds']:.1f} s "
          f"({result['functions_compiled']} functions): numba's front end {front:.1f} s, "
          f"LLVM {result['llvm_seconds']:.1f} s")
    print(f"{'self s':>8} {'incl. s':>8} {'sigs':>4}  function")
    for row in result["functions"][:args.top]:
        print(f"{row['self_seconds']:8.1f} {row['inclusive_seconds']:8.1f} {row['signatures']:4d}  {row['function']}")
    if args.json:
        Path(args.json).write_text(json.dumps(result, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
