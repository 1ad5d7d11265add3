"""Kernels compiled when the extension was built, shipped inside it: a first render loads them instead of
compiling for minutes.

``make extension`` (``tools/ship_kernels.py``) compiles the warm-up scene's kernels for a portable CPU
level (``engine.tracer.kernel_target``) under the package name "Install from Disk" gives the add-on, and
adds them to the zip of the platform it runs on:

    kernels/manifest.json                 what they were compiled for (see ``unusable``)
    kernels/<level>/<tracer folder>/...   numba's cache files, by folder of the tracer's sources

``adopt()`` runs before any kernel module is imported (``kernel_cache.configure``). When this machine's
own kernels are not compiled yet and the shipped ones fit (same package name, tracer sources, numba,
platform and Python, and a CPU with the level's features), it copies them into the user's kernel cache
(numba's cache must be writable, the extension's folder may not be) and makes the process compile and
load kernels for that level. The background warm-up still compiles this CPU's own kernels, a few per cent
faster, which the next session uses. Imports no numba (llvmlite only, to ask the CPU's features).
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

from ..tracer import kernel_folder, kernel_target

ADDON_ROOT = Path(__file__).resolve().parents[2]
FOLDER = "kernels"
MANIFEST = "manifest.json"
#: numba's cache files: an index per function and the compiled code it lists.
CACHE_PATTERNS = ("*.nbi", "*.nbc")


def read_manifest(root: Path = ADDON_ROOT) -> dict | None:
    """The shipped kernels' manifest, or None when the extension ships none (or it cannot be read)."""
    try:
        return json.loads((root / FOLDER / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def unusable(manifest: dict) -> str | None:
    """Why the kernels ``manifest`` describes cannot load in this process, or None when they can."""
    checks = (
        ("package", kernel_folder.package_name(), "the add-on's package name"),
        ("fingerprint", kernel_folder.source_fingerprint(), "the tracer's sources, numba or llvmlite"),
        ("machine", kernel_target.machine(), "the platform or Python"),
    )
    for key, here, what in checks:
        if manifest.get(key) != here:
            return f"{what} differ ({manifest.get(key)!r} shipped, {here!r} here)"
    target = manifest.get("target")
    if target not in kernel_target.PORTABLE_FEATURES:
        return f"unknown CPU level {target!r}"
    if not kernel_target.host_supports(target):
        return f"this CPU lacks features of {target}"
    return None


def install(manifest: dict, root: Path = ADDON_ROOT) -> int:
    """Copy the shipped kernels into the user's cache for their CPU level and mark it warm; files copied.

    Each tracer folder's files go where numba looks for that folder's kernels (its name carries the
    folder's absolute path, which differs from machine to machine). Each file is written under a temporary
    name and renamed into place, as numba writes its own (another Blender adopting at the same moment, or
    reading, finds a file whole or not at all); compiled code first, indexes last, the stamp after all: an
    interrupted copy leaves at worst an index whose code numba compiles again."""
    target = manifest["target"]
    shipped = root / FOLDER / target
    tracer_root = kernel_folder.tracer_root()
    destination = kernel_folder.numba_directory(target)
    files = sorted((p for pattern in CACHE_PATTERNS for p in shipped.rglob(pattern)), key=lambda p: p.suffix == ".nbi")
    for path in files:
        relative = path.parent.relative_to(shipped)
        folder = destination / kernel_folder.numba_subfolder(tracer_root / relative)
        folder.mkdir(parents=True, exist_ok=True)
        partial = folder / f"{path.name}.{os.getpid()}.tmp"
        shutil.copyfile(path, partial)
        os.replace(partial, folder / path.name)
    kernel_folder.mark_cache_warm(target)
    return len(files)


def adopt(root: Path = ADDON_ROOT) -> str | None:
    """Use the shipped kernels in this process if this CPU's own are not compiled yet and they fit; the
    CPU level they were compiled for, or None (this CPU's kernels are used, compiled or not)."""
    if kernel_folder.cache_is_warm(kernel_target.HOST):
        return None
    manifest = read_manifest(root)
    if manifest is None or unusable(manifest) is not None:
        return None
    target = manifest["target"]
    if not kernel_folder.cache_is_warm(target):
        install(manifest, root)
    kernel_target.use(target)
    return target
