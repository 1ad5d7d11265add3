"""Where a cold compile's seconds go, from numba's own compile events.

``CompileRecorder().install()`` listens (before the first kernel compiles) to numba's event API
(``numba.core.event``):

- ``numba:compile``: one per function and signature numba compiles. Events nest (a kernel's callees
  compile while its types are inferred), so each function gets *inclusive* seconds and *self* seconds
  (inclusive less the callees that compiled inside it). A function marked ``jit.inlined`` has no event of
  its own: numba copies and re-types its body into every caller, so its cost shows in the callers' self
  seconds, once per call site.
- ``numba:llvm_lock``: held while LLVM optimises and generates machine code. Its outermost intervals
  add up to the LLVM share of the compile; the rest is numba's front end (bytecode analysis, inlining,
  type inference, lowering to LLVM IR).

Used by ``benchmarks.startup`` (the cold figure's split) and ``tools/compile_profile.py`` (per function).
"""

from __future__ import annotations

import threading
import time
from collections import defaultdict


class CompileRecorder:
    """Seconds numba spends compiling in this process, per function and in LLVM."""

    def __init__(self):
        self.compiled = []  # (function, signature text, inclusive s, self s)
        self.llvm_seconds = 0.0
        self._stacks = defaultdict(list)  # per thread: [function, signature, start, callees' seconds]
        self._llvm_depth = defaultdict(int)
        self._llvm_start = {}
        self._listeners = []

    def install(self):
        """Register with numba's event API (imports numba); returns self."""
        from numba.core import event

        recorder = self

        class _Compile(event.Listener):
            def on_start(self, ev):
                recorder._compile_started(ev.data or {})

            def on_end(self, ev):
                recorder._compile_ended()

        class _Llvm(event.Listener):
            def on_start(self, ev):
                recorder._llvm_started()

            def on_end(self, ev):
                recorder._llvm_ended()

        self._listeners = [("numba:compile", _Compile()), ("numba:llvm_lock", _Llvm())]
        for kind, listener in self._listeners:
            event.register(kind, listener)
        return self

    def uninstall(self):
        """Stop listening."""
        from numba.core import event

        for kind, listener in self._listeners:
            event.unregister(kind, listener)
        self._listeners = []

    def _compile_started(self, data):
        function = getattr(data.get("dispatcher"), "py_func", None)
        name = f"{function.__module__}.{function.__qualname__}" if function else "?"
        self._stacks[threading.get_ident()].append([name, str(data.get("args")), time.perf_counter(), 0.0])

    def _compile_ended(self):
        stack = self._stacks[threading.get_ident()]
        name, signature, start, callees = stack.pop()
        seconds = time.perf_counter() - start
        if stack:
            stack[-1][3] += seconds
        self.compiled.append((name, signature, seconds, seconds - callees))

    def _llvm_started(self):
        thread = threading.get_ident()
        if self._llvm_depth[thread] == 0:
            self._llvm_start[thread] = time.perf_counter()
        self._llvm_depth[thread] += 1

    def _llvm_ended(self):
        thread = threading.get_ident()
        self._llvm_depth[thread] -= 1
        if self._llvm_depth[thread] == 0:
            self.llvm_seconds += time.perf_counter() - self._llvm_start[thread]

    @property
    def compile_seconds(self) -> float:
        """Seconds inside outermost compiles (every function's self seconds added)."""
        return sum(entry[3] for entry in self.compiled)

    def by_function(self) -> list[tuple[str, int, float, float]]:
        """(function, signatures compiled, self s, inclusive s (callees included)), most self seconds first."""
        totals = defaultdict(lambda: [0, 0.0, 0.0])
        for name, _, inclusive, own in self.compiled:
            entry = totals[name]
            entry[0] += 1
            entry[1] += own
            entry[2] += inclusive
        return sorted(((name, n, own, inclusive) for name, (n, own, inclusive) in totals.items()),
                      key=lambda row: -row[2])

    def summary(self) -> dict:
        """The figures ``benchmarks.startup`` reports: compile and LLVM seconds, functions compiled."""
        return dict(compile_seconds=self.compile_seconds, llvm_seconds=self.llvm_seconds,
                    functions_compiled=len(self.compiled))
