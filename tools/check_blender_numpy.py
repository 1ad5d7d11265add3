"""Check that a zip's runtime wheels import and run with the numpy of every supported Blender.

    python tools/check_blender_numpy.py                      # linux-x64 pins, Blender 4.2 and 5.0 numpy
    python tools/check_blender_numpy.py --pins-of macos-x64  # the macOS x86-64 numba/llvmlite, run on Linux

Runs on Linux x86-64 (it executes the wheels). For each numpy of ``extension_wheels.BLENDER_NUMPY``
it makes a virtual environment under ``build/numpy-check/``, installs the Linux wheels of the
platform's pins (the same versions the zip of ``--pins-of`` bundles, built for Linux) and that
numpy, and in it: imports every bundled package, compiles and runs a tracer kernel (the
refractive index of N-BK7 at the d line), traces one ray with embreex and evaluates a spectrum
with colour-science. Prints one line per numpy and exits non-zero if any fails.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import extension_wheels as ew  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

_PROBE = r'''
import json, sys
import numpy as np
import numba, llvmlite, scipy.special, colour, embreex, PIL, imageio
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh
from engine.tracer.spectra import dispersion

# N-BK7 (SCHOTT): n_d = 1.5168 at 587.56 nm.
row = np.array([1.0, 300.0, 2500.0, 1.03961212, 0.231792344, 1.01046945,
                0.00600069867, 0.0200179144, 103.560653])
n_d, clamped = dispersion.refractive_index(row, 587.56)
assert abs(n_d - 1.5168) < 1e-4 and not clamped, n_d

scene = rtcore_scene.EmbreeScene()
TriangleMesh(scene, np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.int32))
hit = scene.run(np.array([[0, 0, 1]], np.float32), np.array([[0, 0, -1]], np.float32), output=1)
assert hit["primID"][0] == 0 and abs(hit["tfar"][0] - 1.0) < 1e-6, hit

xyz = colour.sd_to_XYZ(colour.sd_blackbody(6500.0))
assert np.all(np.isfinite(xyz)) and abs(float(scipy.special.ndtri(0.5))) < 1e-12
print(json.dumps({"numpy": np.__version__, "numba": numba.__version__, "llvmlite": llvmlite.__version__,
                  "scipy": scipy.__version__, "colour": colour.__version__, "n_d": n_d}))
'''


def _venv_python(directory: Path) -> Path:
    if not (directory / "bin" / "python").exists():
        venv.EnvBuilder(with_pip=True, clear=True).create(directory)
    return directory / "bin" / "python"


def check(pins_of: str, numpy_version: str, wheels_dir: Path, work_dir: Path) -> dict:
    """Install ``pins_of``'s pins (Linux wheels) with ``numpy_version`` and run the probe."""
    requirement_pins = ew.read_requirement_pins(ROOT / "requirements.txt")
    pins = ew.resolve_wheels(pins_of, requirement_pins, wheels_dir)
    linux = ew.ensure_wheels(list(pins), "linux-x64", wheels_dir)
    python = _venv_python(work_dir / f"{pins_of}-numpy-{numpy_version}")
    install = [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
               "--no-deps", "--only-binary=:all:", f"numpy=={numpy_version}", *map(str, linux.values())]
    subprocess.run(install, check=True)
    with tempfile.TemporaryDirectory() as cache:
        result = subprocess.run([str(python), "-c", _PROBE], capture_output=True, text=True, cwd=ROOT,
                                env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(ROOT),
                                     "PRISM_KERNEL_CACHE": cache, "HOME": cache})
    if result.returncode != 0:
        return {"numpy": numpy_version, "error": result.stderr.strip().splitlines()[-3:]}
    return json.loads(result.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pins-of", default="linux-x64", choices=sorted(ew.ZIP_PINS),
                        help="whose pinned versions to check (default linux-x64)")
    parser.add_argument("--numpy", action="append", metavar="VERSION",
                        help="numpy version(s) to check (default: Blender's, BLENDER_NUMPY)")
    parser.add_argument("--wheels-dir", type=Path, default=ROOT / "wheels")
    parser.add_argument("--work-dir", type=Path, default=ROOT / "build" / "numpy-check")
    args = parser.parse_args(argv)
    if sys.platform != "linux":
        print("error: this check runs the Linux x86-64 wheels; run it on Linux", file=sys.stderr)
        return 1
    failed = False
    for numpy_version in args.numpy or sorted(set(ew.BLENDER_NUMPY.values())):
        try:
            outcome = check(args.pins_of, numpy_version, args.wheels_dir, args.work_dir)
        except (ew.WheelError, subprocess.CalledProcessError) as error:
            outcome = {"numpy": numpy_version, "error": str(error)}
        failed |= "error" in outcome
        print(f"{args.pins_of} pins with numpy {numpy_version}: "
              + ("FAILED " + json.dumps(outcome["error"]) if "error" in outcome else json.dumps(outcome)),
              flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
