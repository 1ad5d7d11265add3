"""The media experiment's arithmetic on synthetic renders whose noise and times are known: the equal-time ratio
and relMSE x seconds come out as the noise and the times say (no bpy, no renderer)."""

import numpy as np
import pytest

from benchmarks.experiments.media_vs_cycles import measure
from helpers.synthetic_renders import two_renderers as _renders


def test_twice_the_time_for_the_same_noise_is_twice_the_relmse_at_equal_time():
    rows, found = measure(_renders(seconds_per_spp=(0.02, 0.01), noise=(0.5, 0.5)))
    assert found["equal_time"] == pytest.approx(2.0, rel=0.05)
    assert found["prism"]["relmse_s"] / found["cycles"]["relmse_s"] == pytest.approx(2.0, rel=0.05)
    assert found["prism"]["slope"] == pytest.approx(-1.0, abs=0.05)
    assert found["prism"]["s_per_spp"] == pytest.approx(0.02)
    assert len(rows) == 8 and "Prism / Cycles at equal time" in rows[0] and "Cycles relMSE at these s" not in rows[-1]


def test_less_noise_in_the_same_time_is_a_ratio_below_one():
    _, found = measure(_renders(seconds_per_spp=(0.01, 0.01), noise=(0.3, 0.6)))
    assert found["equal_time"] == pytest.approx(0.25, rel=0.05)
    assert found["prism"]["luminance"] == pytest.approx(found["cycles"]["luminance"], rel=0.01)
