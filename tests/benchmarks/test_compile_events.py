"""The compile recorder behind the cold-compile split of ``benchmarks.startup`` and ``tools/compile_profile.py``."""

import numba

from benchmarks.compile_events import CompileRecorder


def test_a_callee_compiled_inside_its_caller_counts_once_in_self_seconds():
    @numba.njit(cache=False)
    def callee(x):
        return x * 2.0 + 1.0

    @numba.njit(cache=False)
    def caller(x):
        return callee(x) - callee(x + 1.0)

    recorder = CompileRecorder().install()
    try:
        assert caller(1.0) == -2.0
    finally:
        recorder.uninstall()
    names = [entry[0].rsplit(".", 1)[-1] for entry in recorder.compiled]
    assert names == ["callee", "caller"]  # the callee's compile ends first, inside the caller's
    (_, _, callee_inclusive, callee_self), (_, _, caller_inclusive, caller_self) = recorder.compiled
    assert callee_self == callee_inclusive > 0.0
    assert abs(caller_self - (caller_inclusive - callee_inclusive)) < 1e-9
    assert abs(recorder.compile_seconds - caller_inclusive) < 1e-9  # self seconds add up to the outermost compile
    assert 0.0 < recorder.llvm_seconds < caller_inclusive
    summary = recorder.summary()
    assert summary["functions_compiled"] == 2
    by_function = dict((name.rsplit(".", 1)[-1], (n, own)) for name, n, own, _ in recorder.by_function())
    assert by_function["caller"] == (1, caller_self)


def test_nothing_is_recorded_after_uninstall():
    recorder = CompileRecorder().install()
    recorder.uninstall()

    @numba.njit(cache=False)
    def late(x):
        return x + 1

    assert late(1) == 2
    assert recorder.compiled == [] and recorder.llvm_seconds == 0.0
