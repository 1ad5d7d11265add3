"""Ctrl-C (SIGINT) and SIGTERM in a batch run: stop cleanly, never leave a half-written file.

The first signal asks the render to stop (the session polls ``stop_requested``
between chunks); the batch script then writes nothing under the output's name
and exits with 128 + the signal number. A second signal exits at once, after
deleting the temporary files still registered here.
"""

from __future__ import annotations

import signal
import sys
import threading
from pathlib import Path

from .process_exit import exit_now

_SIGNALS = tuple(s for s in (getattr(signal, "SIGINT", None), getattr(signal, "SIGTERM", None)) if s is not None)
#: Exit status of a run stopped by Esc inside Blender (no signal reached Python): as Ctrl-C.
INTERRUPTED_STATUS = 128 + signal.SIGINT


class Interrupted(Exception):
    """The run was stopped; ``status`` is the exit status to return."""

    def __init__(self, message: str, status: int = INTERRUPTED_STATUS):
        super().__init__(message)
        self.status = status


class StopSignals:
    """``with StopSignals() as signals:`` catches SIGINT/SIGTERM for the block (main thread only)."""

    def __init__(self):
        self.signal_number: int | None = None
        self.temporary_files: set[Path] = set()
        self._previous: dict[int, object] = {}

    def __enter__(self) -> StopSignals:
        if threading.current_thread() is threading.main_thread():
            for number in _SIGNALS:
                self._previous[number] = signal.signal(number, self._handle)
        return self

    def __exit__(self, *exc) -> bool:
        for number, previous in self._previous.items():
            if previous is not None:  # None: a handler installed outside Python, which cannot be put back
                signal.signal(number, previous)
        return False

    def stop_requested(self) -> bool:
        return self.signal_number is not None

    @property
    def exit_status(self) -> int:
        return 128 + (self.signal_number or signal.SIGINT)

    def raise_if_stopped(self, what: str) -> None:
        """Raise ``Interrupted`` (saying that ``what`` was not written) once a signal came."""
        if self.stop_requested():
            raise Interrupted(f"interrupted by {self.signal_name()}: {what} was not written.", self.exit_status)

    def signal_name(self) -> str:
        return signal.Signals(self.signal_number or signal.SIGINT).name

    def _handle(self, number, _frame) -> None:
        if self.signal_number is not None:
            self._exit_now(number)
        self.signal_number = number
        print(
            f"Prism: {signal.Signals(number).name} received: stopping after the current chunk; "
            "finished files are kept, unfinished ones are not written. Send it again to quit at once.",
            file=sys.stderr,
            flush=True,
        )

    def _exit_now(self, number) -> None:
        for path in list(self.temporary_files):
            try:
                path.unlink()
            except OSError:
                pass
        print(f"Prism: {signal.Signals(number).name} again: quitting now.", file=sys.stderr, flush=True)
        exit_now(128 + number)
