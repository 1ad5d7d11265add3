"""Compiled kernels: the one decorator every numba function of the tracer uses, and their disk cache.

numba is imported by this module only, and this module only by kernel modules, so nothing compiles or
imports numba until a render needs it (never at Blender start-up). Compiled machine code is cached on
disk so only the first render on a machine pays for compilation:

- ``configure_cache(directory)`` chooses the cache directory; it must be called before the first kernel
  module is imported (Blender passes a folder under the extension's user directory, which is writable
  even when the extension itself is installed read-only). Without it the directory is
  ``$PRISM_KERNEL_CACHE``, else ``$NUMBA_CACHE_DIR``, else a per-user cache folder
  (``~/.cache/prism-spectral/kernels`` on Linux, ``~/Library/Caches/...`` on macOS,
  ``%LOCALAPPDATA%\\prism-spectral\\kernels`` on Windows).
- ``cache_is_warm()`` says whether this exact tracer source was compiled into that directory before,
  so the first render can say "Compiling Prism kernels (first render only)"; ``mark_cache_warm()`` records
  it after a render compiled everything.

Kernel options: ``nogil`` (chunks run on threads), ``cache``, numpy's error model (a division by zero
gives inf or NaN, which the film counts and drops, instead of raising inside a kernel). No fastmath:
NaN checks must stay meaningful and the image must not depend on reassociation.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

_TRACER_ROOT = Path(__file__).resolve().parent
_configured_directory: Path | None = None
_STAMP_PREFIX = "prism-kernels-"


def _default_cache_directory() -> Path:
    for variable in ("PRISM_KERNEL_CACHE", "NUMBA_CACHE_DIR"):
        if os.environ.get(variable):
            return Path(os.environ[variable])
    home = Path.home()
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA") or home / "AppData" / "Local")
    elif sys.platform == "darwin":
        base = home / "Library" / "Caches"
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or home / ".cache")
    return base / "prism-spectral" / "kernels"


def cache_directory() -> Path:
    """Where compiled kernels are cached (see the module docstring)."""
    return _configured_directory or _default_cache_directory()


def configure_cache(directory) -> None:
    """Cache compiled kernels in ``directory`` (created if needed). Call before any kernel module is
    imported; afterwards it only takes effect for kernels compiled from then on."""
    global _configured_directory
    path = Path(directory)
    path.mkdir(parents=True, exist_ok=True)
    _configured_directory = path
    os.environ["NUMBA_CACHE_DIR"] = str(path)
    if "numba" in sys.modules:
        sys.modules["numba"].config.CACHE_DIR = str(path)


def _prepare_numba():
    directory = cache_directory()
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError:
        return  # numba falls back to __pycache__ next to the sources, or compiles in memory
    os.environ.setdefault("NUMBA_CACHE_DIR", str(directory))
    import numba

    numba.config.CACHE_DIR = str(directory)


_prepare_numba()

import numba  # noqa: E402  (after the cache directory is set)

#: Decorator for kernels and the per-path functions they call.
kernel = numba.njit(nogil=True, cache=True, error_model="numpy")


def source_fingerprint() -> str:
    """Hash of the tracer's sources and the numba/llvmlite versions: changes whenever kernels recompile."""
    digest = hashlib.sha256()
    digest.update(numba.__version__.encode())
    for path in sorted(_TRACER_ROOT.rglob("*.py")):
        digest.update(str(path.relative_to(_TRACER_ROOT)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _stamp() -> Path:
    return cache_directory() / f"{_STAMP_PREFIX}{source_fingerprint()}.ok"


def cache_is_warm() -> bool:
    """True if this tracer source was compiled into the cache directory before (a warm start)."""
    return _stamp().exists()


def mark_cache_warm() -> None:
    """Record that every kernel of this tracer source is in the cache (stale stamps are removed)."""
    directory = cache_directory()
    try:
        for old in directory.glob(f"{_STAMP_PREFIX}*.ok"):
            old.unlink(missing_ok=True)
        _stamp().write_text("compiled\n", encoding="utf-8")
    except OSError:
        pass  # a read-only cache only costs the message on the next start
