"""The thread-scaling benchmark: which thread counts it measures, that its GIL clock counts the compiled
chunk calls and puts the stage modules back, and a tiny case end to end."""

import pytest

from benchmarks import scaling
from engine.tracer.stages import light_trace, trace


def test_thread_counts_reach_every_core_and_oversubscribe_small_machines():
    assert scaling.thread_counts(2) == [1, 2, 8, 16]
    assert scaling.thread_counts(6) == [1, 2, 4, 6, 8, 16]
    assert scaling.thread_counts(16) == [1, 2, 4, 8, 16]
    assert scaling.thread_counts(32) == [1, 2, 4, 8, 16, 32]


def test_a_tiny_case_and_the_gil_clock():
    before = (trace.bounce_loop_kernel, trace.camera_kernel, light_trace.light_loop_kernel)
    case = scaling.measure_case("cornell_glass", "tiny", 32, 1, [1, 2], rounds=1, log=lambda _: None)
    assert (trace.bounce_loop_kernel, trace.camera_kernel, light_trace.light_loop_kernel) == before
    assert [r["threads"] for r in case["rows"]] == [1, 2]
    assert case["rows"][0]["prism_speedup"] == 1.0 and case["rows"][0]["embree_speedup"] == 1.0
    assert all(r["paths_per_second"] > 0 and r["embree_seconds"] > 0 for r in case["rows"])
    assert case["rays"] > 32 * 32  # camera rays and more were recorded for the replay
    # nearly all of a pass's CPU time is inside the compiled calls: the share outside is a few per cent
    assert set(case["gil_share"]) == {"1", "2"}
    assert all(0.0 <= s < 0.5 for s in case["gil_share"].values()), case["gil_share"]
    table = scaling.scaling_table(dict(cores=2, counts=[1, 2], cases=[case]))
    assert "cornell_glass 32x32, 1 spp" in table and "| Prism paths/s |" in table
