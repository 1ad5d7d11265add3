"""Where compiled kernels are cached, and whether this tracer source's kernels are there: without numba.

``jit`` (which imports numba) re-exports these functions; the add-on calls this module directly when it
must know whether the cache is warm without importing numba into Blender's process (registering the
add-on, a scene switching to Prism: the background kernel warm-up, ``engine.warmup``).

- ``configure_cache(directory)`` chooses the cache directory (before the first kernel module is imported).
  Without it the directory is ``$PRISM_KERNEL_CACHE``, else ``$NUMBA_CACHE_DIR``, else a per-user cache
  folder (``~/.cache/prism-spectral/kernels`` on Linux, ``~/Library/Caches/...`` on macOS,
  ``%LOCALAPPDATA%\\prism-spectral\\kernels`` on Windows). ``prepare_kernel_directory()`` creates it and
  refuses, naming the variable, a folder chosen through one of those variables that cannot be used.
- ``kernel_directory()``: the subfolder of this copy of the tracer (its package name and install
  location) and this version of its sources (``source_fingerprint()``).
- ``numba_directory()``: where numba caches them for the process's CPU target (``kernel_target``).
- ``cache_is_warm()`` / ``mark_cache_warm()``: the stamp file saying every kernel of this source is cached.
"""

from __future__ import annotations

import hashlib
import os
import sys
from importlib import metadata
from pathlib import Path

from . import kernel_target

_TRACER_ROOT = Path(__file__).resolve().parent
_configured_directory: Path | None = None
_STAMP_PREFIX = "prism-kernels-"

# The package this copy of the tracer was imported as: "" for ``engine.tracer`` (tests, tools),
# "prism_spectral" or "bl_ext.<repository>.prism_spectral" in Blender. numba's cache index pickles the
# kernels' argument types by module name, so one source file imported under two names must not share
# an index (the other name may not be importable in the next process): each name gets its folder.
_SUFFIX = "engine.tracer.kernel_folder"
_PACKAGE = __name__[: -len(_SUFFIX)].rstrip(".") if __name__.endswith(_SUFFIX) else __name__


def package_name() -> str:
    """The package the add-on was imported as ("" when the tracer is imported as ``engine.tracer``)."""
    return _PACKAGE


CACHE_VARIABLES = ("PRISM_KERNEL_CACHE", "NUMBA_CACHE_DIR")


def _chosen_variable() -> str | None:
    """The environment variable the cache directory comes from, or None (configured, or the default)."""
    if _configured_directory is not None:
        return None
    return next((variable for variable in CACHE_VARIABLES if os.environ.get(variable)), None)


def _default_cache_directory() -> Path:
    for variable in CACHE_VARIABLES:
        if os.environ.get(variable):
            return Path(os.environ[variable])
    return _per_user_directory()


def _per_user_directory() -> Path:
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


def prepare_kernel_directory() -> bool:
    """Create ``numba_directory()``; True if kernels can be cached there. A folder the user chose through
    ``$PRISM_KERNEL_CACHE`` (or ``$NUMBA_CACHE_DIR``) that cannot be used raises ``PrismInputError`` naming
    the variable and the path: the kernels would otherwise land somewhere else without a word (numba falls
    back to ``__pycache__`` beside the sources). False for an unusable default folder (kernels compile
    every time, the first-render notice says so)."""
    directory = numba_directory()
    try:
        directory.mkdir(parents=True, exist_ok=True)
        if os.access(directory, os.W_OK):
            return True
        problem = "it is not writable"
    except OSError as error:
        problem = error.strerror or str(error)
    variable = _chosen_variable()
    if variable is None:
        return False
    from .errors import PrismInputError

    chosen = Path(os.environ[variable])
    if chosen.exists() and not chosen.is_dir():
        problem = "it is a file, not a folder"
    elif any(parent.exists() and not parent.is_dir() for parent in chosen.parents):
        problem = "a file stands where one of its folders should be"
    raise PrismInputError(
        f"{variable} is '{chosen}', where Prism cannot keep its compiled kernels ({problem}): point {variable} at "
        f"a folder you can write to (it is created if missing), or unset it to use {_per_user_directory()}."
    )


def configure_cache(directory) -> None:
    """Cache compiled kernels in ``directory`` (created if needed). Call before any kernel module is
    imported; afterwards it only takes effect for kernels compiled from then on."""
    global _configured_directory
    path = Path(directory)
    path.mkdir(parents=True, exist_ok=True)
    _configured_directory = path


def kernel_directory() -> Path:
    """The folder this copy of the tracer caches its kernels in: ``cache_directory()`` / package name and
    install location / source fingerprint. numba checks a cached function against its own file only, while kernels inline
    functions from other files: one folder per version of the whole tracer keeps a change anywhere from
    reusing stale machine code (older versions' folders are removed by ``mark_cache_warm``)."""
    return _package_directory() / source_fingerprint()


def numba_directory(target: str | None = ...) -> Path:
    """Where numba caches the kernels compiled for ``target`` (default: this process's,
    ``kernel_target.current()``): ``kernel_directory()`` for this machine's CPU, its subfolder named after
    a portable level otherwise (numba keys kernels by CPU, so the two never mix; both go with the version)."""
    target = kernel_target.current() if target is ... else target
    return kernel_directory() if target is kernel_target.HOST else kernel_directory() / target


def numba_subfolder(source_folder: Path) -> str:
    """The subfolder of the numba directory where numba caches the kernels of the modules in
    ``source_folder``: numba names it after the folder and the SHA-1 of its absolute path
    (``numba.core.caching._CacheLocator.get_suitable_cache_subpath``, checked against numba by the tests).
    Shipped kernels are copied there, so this module must know it without importing numba."""
    folder = os.path.abspath(source_folder)
    return f"{os.path.basename(folder)}_{hashlib.sha1(folder.encode()).hexdigest()}"


def tracer_root() -> Path:
    """This tracer's folder as numba sees its sources (absolute, links not resolved)."""
    return Path(os.path.abspath(os.path.dirname(__file__)))


def tracer_source_folders(root: Path | None = None) -> list[Path]:
    """Every folder of the tracer's sources under ``root`` (default ``tracer_root()``; a staged copy's, for the
    build): the root first."""
    root = Path(os.path.abspath(root or tracer_root()))
    return [root, *sorted(p for p in root.rglob("*") if p.is_dir() and p.name != "__pycache__")]


def _package_directory() -> Path:
    # One folder per package name and per install location: cleaning up one checkout's old versions
    # (``mark_cache_warm``) never removes another checkout's kernels.
    location = hashlib.sha256(str(_TRACER_ROOT).encode()).hexdigest()[:8]
    return cache_directory() / f"{_PACKAGE or 'engine'}-{location}"


def _version(distribution: str) -> str:
    # From the installed distribution's metadata, so that no numba is imported to read it (Blender's
    # extension wheels and pip installs both carry it); the module's own attribute where there is none.
    try:
        return metadata.version(distribution)
    except metadata.PackageNotFoundError:
        import importlib

        return str(getattr(importlib.import_module(distribution), "__version__", "unknown"))


_FINGERPRINT: list[str] = []


def source_fingerprint() -> str:
    """Hash of the tracer's sources and the numba/llvmlite versions: changes whenever kernels recompile
    (hashing the ~1 MB of sources takes a few milliseconds, once per process)."""
    if not _FINGERPRINT:
        digest = hashlib.sha256()
        digest.update(f"{_version('numba')} {_version('llvmlite')}".encode())
        for path in sorted(_TRACER_ROOT.rglob("*.py")):
            digest.update(str(path.relative_to(_TRACER_ROOT)).encode())
            digest.update(path.read_bytes())
        _FINGERPRINT.append(digest.hexdigest()[:16])
    return _FINGERPRINT[0]


def _stamp(target: str | None = ...) -> Path:
    return numba_directory(target) / f"{_STAMP_PREFIX}{source_fingerprint()}.ok"


def cache_is_warm(target: str | None = ...) -> bool:
    """True if this tracer source was compiled for ``target`` (default: this process's CPU target) into
    the cache directory before (a warm start)."""
    return _stamp(target).exists()


def mark_cache_warm(target: str | None = ...) -> None:
    """Record that every kernel of this tracer source is in the cache for ``target`` (default: this
    process's); remove older versions' kernels."""
    import shutil

    current = kernel_directory()
    try:
        numba_directory(target).mkdir(parents=True, exist_ok=True)
        for folder in _package_directory().iterdir():
            if folder.is_dir() and folder != current and len(folder.name) == len(current.name):
                shutil.rmtree(folder, ignore_errors=True)
        _stamp(target).write_text("compiled\n", encoding="utf-8")
    except OSError:
        pass  # a read-only cache only costs the message on the next start
