"""The fast row helpers of the wavefront loop agree with the plain numpy forms."""

import numpy as np

from engine.tracer.path_state import add_rows, compact
from engine.tracer.sampling import row_max, row_sum, rows_finite, where_rows
from engine.tracer.path_spectra import PathWavelengths, cached


def test_row_reductions_match_numpy():
    rng = np.random.default_rng(0)
    for k in (1, 3, 4, 16):
        a = rng.standard_normal((50, k))
        a[3, 0] = np.nan
        a[7, k - 1] = np.inf
        assert np.array_equal(row_max(a)[8:], a.max(axis=1)[8:])
        assert np.allclose(row_sum(a)[8:], a.sum(axis=1)[8:])
        assert np.array_equal(rows_finite(a), np.isfinite(a).all(axis=1))


def test_where_rows_matches_np_where_for_every_mix():
    rng = np.random.default_rng(1)
    for _ in range(100):
        n, k = int(rng.integers(1, 60)), int(rng.integers(1, 5))
        mask = rng.random(n) < rng.choice([0.0, 0.05, 0.5, 0.95, 1.0])
        a, b = rng.random((n, k)), rng.random((n, k))
        for x, y in ((a, b), (a, 0.0), (1.0, b), (a, b[:, :1])):
            out = where_rows(mask, x, y)
            assert np.array_equal(out, np.where(mask[:, None], x, y))
            assert out is not x and out is not y


def test_add_rows_scatters_into_wavelength_major_totals():
    total = np.zeros((3, 10))
    add_rows(total, np.array([1, 4, 9]), np.arange(9.0).reshape(3, 3))
    expected = np.zeros((10, 3))
    expected[[1, 4, 9]] = np.arange(9.0).reshape(3, 3)
    assert np.array_equal(total.T, expected)


def test_compacted_and_taken_wavelengths_keep_their_spectrum_cache():
    lam = PathWavelengths(np.linspace(400.0, 700.0, 20).reshape(10, 2))
    calls = []

    def spectrum(wl):
        calls.append(len(wl))
        return wl / 1000.0

    keep = np.arange(10) % 3 != 0
    (sub,) = compact(keep, lam)
    taken = np.take(sub, np.array([0, 2]), axis=0)
    assert np.array_equal(cached("s", spectrum, sub), np.asarray(lam)[keep] / 1000.0)
    assert np.array_equal(cached("s", spectrum, taken), np.asarray(lam)[keep][[0, 2]] / 1000.0)
    assert calls == [10]  # evaluated once, for the whole chunk
