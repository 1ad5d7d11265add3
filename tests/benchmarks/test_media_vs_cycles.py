"""The media experiment's arithmetic on synthetic renders whose noise and times are known: the equal-time ratio
and relMSE x seconds come out as the noise and the times say (no bpy, no renderer)."""

import numpy as np
import pytest

from benchmarks.experiments.media_vs_cycles import measure


def _renders(seconds_per_spp, noise, spps=(16, 32, 64, 128), shape=(48, 64, 3), seed=0):
    """Two renderers' images [renderer, spp, seed, H, W, 3] of a 0.2-1.0 image with relative noise
    noise[r] / sqrt(spp), and times seconds_per_spp[r] x spp."""
    rng = np.random.default_rng(seed)
    truth = rng.uniform(0.2, 1.0, shape)
    images = np.stack([np.stack([truth * (1 + rng.normal(0.0, n / np.sqrt(spp), (2, *shape))) for spp in spps])
                       for n in noise])
    seconds = np.stack([[[t * spp] * 2 for spp in spps] for t in seconds_per_spp])
    return {"images": images, "seconds": seconds, "spp": np.array(spps), "renderers": np.array(["prism", "cycles"])}


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
