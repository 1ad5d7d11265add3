"""The path sampler: uniform (chi-square), stratified per pixel (a (0,2)-sequence in every 2-D slot),
decorrelated across slots and pixels, deterministic."""

import numpy as np
import pytest
from scipy import stats

from engine.tracer import sampler as s


def _points(kind, pixel, slot, count, start=0, seed=0):
    ps = s.pixel_seed(pixel, seed)
    return np.array([s.sample_2d(kind, ps, i, slot) for i in range(start, start + count)])


def test_sobol_dimension_one_is_the_pascal_matrix():
    # x + 1 direction numbers 1/2, 3/4, 5/8: points 0, 1/2, 3/4, 1/4, 5/8
    v = [s.sobol_dimension_1(i) / 2**32 for i in range(5)]
    assert v == [0.0, 0.5, 0.75, 0.25, 0.625]


def test_scrambling_is_a_bijection_on_32_bit_integers_sampled():
    x = np.arange(0, 1 << 20, 7)
    out = np.array([s.nested_uniform_scramble(int(v), 12345) for v in x])
    assert len(np.unique(out)) == len(x) and out.min() >= 0 and out.max() < 2**32
    assert [s.reverse_bits32(s.reverse_bits32(int(v))) for v in x[:50]] == list(x[:50])


def test_bit_reversal_reverses_the_low_32_bits():
    rng = np.random.default_rng(3)
    for value in [0, 1, 2**31, 2**32 - 1, 0x12345678, 2**32 + 5, *rng.integers(0, 2**40, 200).tolist()]:
        assert s.reverse_bits32(value) == int(format(value & 0xFFFFFFFF, "032b")[::-1], 2), value


@pytest.mark.parametrize("count", [16, 64, 256])
def test_every_power_of_two_prefix_is_stratified_in_every_elementary_interval(count):
    log2 = int(np.log2(count))
    for pixel, slot in ((0, 0), (17, 1), (4242, 9), (99, 23)):
        pts = _points(s.SOBOL, pixel, slot, count)
        for kx in range(log2 + 1):
            nx, ny = 2**kx, 2 ** (log2 - kx)
            cells = np.floor(pts[:, 0] * nx) * ny + np.floor(pts[:, 1] * ny)
            assert np.bincount(cells.astype(int), minlength=count).max() == 1, (pixel, slot, nx, ny)


def test_later_passes_keep_stratifying():
    """Samples 64..127 (a second progressive pass) are again one per 8 x 8 cell."""
    pts = _points(s.SOBOL, 5, 3, 64, start=64)
    cells = np.floor(pts[:, 0] * 8) * 8 + np.floor(pts[:, 1] * 8)
    assert np.bincount(cells.astype(int), minlength=64).max() == 1


@pytest.mark.parametrize("kind", [s.SOBOL, s.INDEPENDENT])
def test_uniform_over_pixels_and_slots_chi_square(kind):
    values = np.array([s.sample_2d(kind, s.pixel_seed(p, 7), i, slot)
                       for p in range(64) for i in range(16) for slot in (0, 6, 11)])
    for column in (0, 1):
        h = np.histogram(values[:, column], bins=32, range=(0, 1))[0]
        assert stats.chisquare(h).pvalue > 1e-3
    h2 = np.histogram2d(values[:, 0], values[:, 1], bins=8, range=[[0, 1], [0, 1]])[0]
    assert stats.chisquare(h2.ravel()).pvalue > 1e-3
    one = np.array([s.sample_1d(kind, s.pixel_seed(p, 7), i, 8) for p in range(256) for i in range(8)])
    assert np.all((one >= 0) & (one < 1)) and stats.chisquare(np.histogram(one, bins=32, range=(0, 1))[0]).pvalue > 1e-3


def test_slots_and_pixels_are_decorrelated():
    n = 256
    a = _points(s.SOBOL, 10, 6, n)
    b = _points(s.SOBOL, 10, 7, n)
    c = _points(s.SOBOL, 11, 6, n)
    for x, y in ((a[:, 0], b[:, 0]), (a[:, 1], b[:, 1]), (a[:, 0], c[:, 0]), (a[:, 0], a[:, 1])):
        assert abs(np.corrcoef(x, y)[0, 1]) < 4 / np.sqrt(n)
    # a 1-D slot and the first coordinate of a 2-D slot of the same index are the same number
    assert s.sample_1d(s.SOBOL, 3, 5, 9) == s.sample_2d(s.SOBOL, 3, 5, 9)[0]


def test_sobol_beats_independent_on_a_smooth_integrand():
    """Mean squared error of estimating the integral of a smooth 2-D function with 64 samples per pixel."""
    def f(p):
        return np.exp(-((p[:, 0] - 0.3) ** 2 + (p[:, 1] - 0.6) ** 2) * 4.0)

    truth = 0.5048914401783491  # integral of f over the unit square (scipy dblquad, error 8e-15)
    err = {}
    for kind in (s.SOBOL, s.INDEPENDENT):
        est = np.array([f(_points(kind, p, 2, 64)).mean() for p in range(200)])
        err[kind] = np.mean((est - truth) ** 2)
    assert err[s.SOBOL] < 0.1 * err[s.INDEPENDENT], err


def test_seed_changes_everything_and_is_deterministic():
    a = _points(s.SOBOL, 1, 1, 8, seed=1)
    assert np.array_equal(a, _points(s.SOBOL, 1, 1, 8, seed=1))
    assert not np.any(a == _points(s.SOBOL, 1, 1, 8, seed=2))
