"""Start the background kernel warm-up, say whether one is running, wait for it.

Standard library and ``engine.tracer.kernel_folder`` only (no bpy, no numba): Blender's process calls it
when a scene switches to Prism, and the render session before its first kernel.

``start()`` runs ``child.py`` with ``sys.executable`` (Blender's bundled Python) when this tracer source
is not in the cache yet and no warm-up holds the lock, with the parent's ``sys.path`` (Blender adds the
extension's wheels to it at run time), the parent's package name and cache directory, its output going
to ``warmup.log`` in the kernel folder. The process is detached from Blender's terminal (Ctrl-C there
does not stop it) and outlives Blender if it has to: the cache it fills serves the next session.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

from . import kernel_cache
from ..tracer import kernel_folder, kernel_target
from . import lock

LOG_NAME = "warmup.log"
ADDON_ROOT = Path(__file__).resolve().parents[2]
CHILD = Path(__file__).resolve().with_name("child.py")
#: Windows creation flags: no console window, below-normal priority, out of Blender's Ctrl-C group.
_WINDOWS_FLAGS = 0x08000000 | 0x00004000 | 0x00000200

#: Processes this Blender started: polled (reaped) before the lock is read, so that a finished one is
#: not mistaken for a live one (an unreaped child is a zombie, which still has its pid).
_started: list[subprocess.Popen] = []


def lock_path() -> Path:
    """The lock file of this tracer source's kernel folder (in the configured cache)."""
    kernel_cache.configure()
    return kernel_folder.kernel_directory() / lock.LOCK_NAME


def log_path() -> Path:
    """The warm-up's log: its output and, at the end, what it compiled and how long it took."""
    return lock_path().with_name(LOG_NAME)


def _reap() -> None:
    _started[:] = [process for process in _started if process.poll() is None]


def running() -> int | None:
    """The pid of the warm-up compiling into this kernel folder now (any Blender's), or None."""
    _reap()
    return lock.holder(lock_path())


def command(cache: Path, lock_file: Path) -> list[str]:
    """The warm-up's command line: this add-on's package and folder, the cache, the lock."""
    return [sys.executable, str(CHILD), "--package", kernel_folder.package_name(), "--root", str(ADDON_ROOT),
            "--cache", str(cache), "--lock", str(lock_file)]


def start() -> subprocess.Popen | None:
    """Start the warm-up process if the cache is cold for this tracer source and none is running; the
    process, or None when none was started."""
    cache = kernel_cache.configure()
    if kernel_folder.cache_is_warm(kernel_target.HOST):  # shipped kernels in use or not: this CPU's are faster
        return None
    _reap()
    lock_file = lock_path()
    try:
        if not lock.acquire(lock_file, os.getpid()):
            return None
    except OSError:
        return None  # a cache folder that cannot be written: the first render compiles, as before
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    options = {"creationflags": _WINDOWS_FLAGS} if sys.platform == "win32" else {"start_new_session": True}
    try:
        with open(lock_file.with_name(LOG_NAME), "w", encoding="utf-8") as log:
            process = subprocess.Popen(command(cache, lock_file), stdin=subprocess.DEVNULL, stdout=log,
                                       stderr=subprocess.STDOUT, env=environment, cwd=str(lock_file.parent),
                                       close_fds=True, **options)
    except OSError:
        lock.release(lock_file, os.getpid())
        return None
    try:
        lock.hand_over(lock_file, process.pid)
    except OSError:
        pass  # the lock keeps this process's pid: held while Blender runs, stale after
    _started.append(process)
    return process


def wait(stop_requested, report, poll_s: float = 0.25) -> bool:
    """Wait for a running warm-up to finish, calling ``report(seconds_waited)`` at each poll; False if
    ``stop_requested()`` said stop first (True at once when none runs)."""
    started = time.monotonic()
    while running() is not None:
        report(time.monotonic() - started)
        if stop_requested():
            return False
        time.sleep(poll_s)
    return True
