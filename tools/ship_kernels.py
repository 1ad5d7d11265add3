"""Compile the kernels a first render needs for a portable CPU level and add them to an extension zip.

    python tools/ship_kernels.py <staged add-on folder> <zip> [--work-dir DIR]

Called by ``build_extension.py`` for the zip of the platform it runs on. It runs the background warm-up
(``engine/warmup/child.py``) on the staged add-on under the package name Blender gives an extension
installed from disk (``bl_ext.user_default.<id>``), compiling for ``x86-64-v3``
(``engine.tracer.kernel_target``), then writes numba's cache files into the zip under ``kernels/``, by
folder of the tracer's sources, with a manifest saying what they fit (``engine.warmup.shipped_kernels``
reads it). One compile, 8-10 minutes on one core: the time a user's first render no longer waits.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from engine.tracer import kernel_folder, kernel_target  # noqa: E402 - no numba: folder names and CPU levels
from engine.warmup import shipped_kernels  # noqa: E402

TARGET = "x86-64-v3"
REPOSITORY = "user_default"  # the repository "Install from Disk" (and drag and drop) installs into
DONE = "Prism kernel warm-up done: "
COMPILE_TIMEOUT_S = 1800


class ShipError(RuntimeError):
    """The kernels could not be compiled or added; the message says why."""


def package_for(addon_id: str) -> str:
    """The package name Blender imports an extension installed from disk as."""
    return f"bl_ext.{REPOSITORY}.{addon_id}"


def compile_kernels(stage: Path, package: str, cache: Path) -> dict:
    """Run the warm-up on the staged add-on for ``TARGET``; its report (kernel and numba directories)."""
    child = stage / "engine" / "warmup" / "child.py"
    command = [sys.executable, str(child), "--package", package, "--root", str(stage), "--cache", str(cache),
               "--cpu-target", TARGET]
    result = subprocess.run(command, capture_output=True, text=True, timeout=COMPILE_TIMEOUT_S)
    done = [line for line in result.stdout.splitlines() if line.startswith(DONE)]
    if result.returncode != 0 or not done:
        raise ShipError(f"the kernel warm-up failed (exit {result.returncode}):\n{result.stdout}{result.stderr}")
    report = json.loads(done[-1][len(DONE):])
    if report.get("already_warm"):
        raise ShipError(f"the cache {cache} was not empty: the kernels must be compiled afresh")
    return report


def cache_files(numba_directory: Path, stage: Path) -> dict[str, Path]:
    """numba's cache files by their place in the zip: ``kernels/<level>/<tracer folder>/<file>``."""
    tracer, *below = kernel_folder.tracer_source_folders(stage / "engine" / "tracer")
    folders = {kernel_folder.numba_subfolder(f): f.relative_to(tracer).as_posix() for f in [tracer, *below]}
    files = {}
    for pattern in shipped_kernels.CACHE_PATTERNS:
        for path in numba_directory.glob(f"*/{pattern}"):
            relative = folders.get(path.parent.name)
            if relative is None:
                raise ShipError(f"{path} is cached for a folder outside the staged tracer")
            files[f"{shipped_kernels.FOLDER}/{TARGET}/{relative}/{path.name}".replace("/./", "/")] = path
    if not files:
        raise ShipError(f"the warm-up cached no kernel in {numba_directory}")
    return files


def ship(stage: Path, zip_path: Path, addon_id: str, work_dir: Path | None = None) -> dict:
    """Compile, then append the kernels and their manifest to ``zip_path``; the manifest."""
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="prism-ship-", dir=work_dir) as scratch:
        report = compile_kernels(stage, package_for(addon_id), Path(scratch))
        numba_directory = Path(report["numba_directory"])
        files = cache_files(numba_directory, stage)
        manifest = {"package": package_for(addon_id), "fingerprint": numba_directory.parent.name,
                    "machine": kernel_target.machine(), "target": TARGET, "files": len(files),
                    "functions_compiled": report["functions_compiled"],
                    "compile_seconds": round(time.perf_counter() - start, 1)}
        with zipfile.ZipFile(zip_path, "a", compression=zipfile.ZIP_DEFLATED) as zf:
            for name, path in sorted(files.items()):
                zf.write(path, name)
            zf.writestr(f"{shipped_kernels.FOLDER}/{shipped_kernels.MANIFEST}", json.dumps(manifest, indent=2))
    return manifest


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stage", type=Path, help="the staged add-on folder the zip was built from")
    parser.add_argument("zip", type=Path)
    parser.add_argument("--id", default="prism_spectral", help="the extension's id (its manifest's `id`)")
    parser.add_argument("--work-dir", type=Path, help="where to compile (a temporary folder inside it)")
    args = parser.parse_args(argv)
    try:
        manifest = ship(args.stage, args.zip, args.id, args.work_dir)
    except (ShipError, subprocess.TimeoutExpired) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    print(json.dumps(manifest, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
