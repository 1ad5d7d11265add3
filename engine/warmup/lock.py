"""The warm-up lock: a file in the kernel folder holding the warm-up process's id (decimal, one line).

At most one warm-up runs per kernel folder: ``acquire`` creates the file exclusively, so two Blender
sessions switching to Prism at once start one process between them. A lock whose process is gone (it
crashed, was killed, or the machine restarted) or that is older than ``STALE_AFTER_S`` (its pid may
have been reused by another program) is stale: ignored and replaced. The process removes its lock when
it ends (``release``). Standard library only: Blender's process reads it.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

LOCK_NAME = "warmup.lock"
#: Seconds after which a lock counts as stale whatever its pid: a cold compile takes 1-6 minutes.
STALE_AFTER_S = 30 * 60


def process_alive(pid: int) -> bool:
    """Whether process ``pid`` exists (a zombie counts as alive: its parent has not reaped it yet)."""
    if pid <= 0:
        return False
    if sys.platform == "win32":
        return _windows_process_alive(pid)
    try:
        os.kill(pid, 0)  # signal 0: existence check only
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # another user's process
    except OSError:
        return False
    return True


def _windows_process_alive(pid: int) -> bool:
    # os.kill(pid, 0) would terminate the process on Windows: ask for its exit code instead.
    import ctypes

    kernel32 = ctypes.windll.kernel32
    handle = kernel32.OpenProcess(0x1000, False, pid)  # PROCESS_QUERY_LIMITED_INFORMATION
    if not handle:
        return False
    try:
        code = ctypes.c_ulong()
        return bool(kernel32.GetExitCodeProcess(handle, ctypes.byref(code))) and code.value == 259  # STILL_ACTIVE
    finally:
        kernel32.CloseHandle(handle)


def holder(path: Path) -> int | None:
    """The pid of the live process holding the lock at ``path`` (0 for a lock being written), or None (no
    lock, or a stale one)."""
    try:
        text = path.read_text(encoding="ascii").strip()
        age_s = time.time() - path.stat().st_mtime
    except (OSError, UnicodeDecodeError):
        return None
    if not text and age_s < 10:
        return 0  # just created, its pid not written yet: held
    try:
        pid = int(text)
    except ValueError:
        return None  # not ours: stale
    if age_s > STALE_AFTER_S or not process_alive(pid):
        return None
    return pid


def acquire(path: Path, pid: int) -> bool:
    """Take the lock for ``pid``: True if taken, False if a live process holds it. A stale lock is replaced."""
    path.parent.mkdir(parents=True, exist_ok=True)
    for _ in range(2):
        try:
            descriptor = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            if holder(path) is not None:
                return False
            try:
                path.unlink()  # stale; if another process replaced it meanwhile, its O_EXCL or ours fails
            except FileNotFoundError:
                pass
            continue
        with os.fdopen(descriptor, "w", encoding="ascii") as file:
            file.write(f"{pid}\n")
        return True
    return False


def hand_over(path: Path, pid: int) -> None:
    """Write ``pid`` (the process just started) into a lock this process holds (atomic replace)."""
    temporary = path.with_name(f"{path.name}.{os.getpid()}")
    temporary.write_text(f"{pid}\n", encoding="ascii")
    os.replace(temporary, path)


def release(path: Path, pid: int) -> None:
    """Remove the lock if ``pid`` holds it."""
    try:
        if path.read_text(encoding="ascii").strip() == str(pid):
            path.unlink()
    except (OSError, UnicodeDecodeError):
        pass
