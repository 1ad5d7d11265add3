"""Film: running mean and variance of the mean per pixel, NaN samples dropped and counted."""

import numpy as np

from engine.tracer.film import Film


def test_mean_and_variance_match_numpy():
    rng = np.random.default_rng(0)
    film = Film(3, 2)
    samples = {p: [] for p in range(6)}
    for _ in range(4):
        pix = np.repeat(np.arange(6), 3)
        rgb = rng.normal(size=(18, 3)) * (pix[:, None] + 1)
        film.add(pix, rgb)
        for p, c in zip(pix, rgb):
            samples[p].append(c)
    mean = film.mean().reshape(6, 3)
    var = film.variance_of_mean().reshape(6, 3)
    for p in range(6):
        s = np.array(samples[p])
        assert np.allclose(mean[p], s.mean(0))
        assert np.allclose(var[p], s.var(0, ddof=1) / len(s))
    assert film.counts.tolist() == [[12, 12, 12], [12, 12, 12]]


def test_non_finite_samples_are_dropped_and_counted():
    film = Film(2, 1)
    film.add(np.array([0, 0, 1, 1]), np.array([[1, 1, 1], [np.nan, 0, 0], [2, 2, 2], [np.inf, 1, 1.0]]))
    assert film.nan_samples == 2
    assert np.allclose(film.mean()[0], [[0.5, 0.5, 0.5], [1, 1, 1]])
    assert np.all(np.isfinite(film.variance_of_mean()))


def test_pass_columns_are_summed_or_kept_as_minima_and_regions_index_the_frame():
    from engine.tracer.passes import FilmLayout, PassRequest

    layout = FilmLayout(PassRequest(("Depth", "Normal")))
    film = Film(10, 8, layout, region=(4, 2, 6, 3))  # two pixels of a 10 x 8 frame: (4, 2) and (5, 2)
    depth, normal = layout.columns["depth"][0], layout.columns["normal"][0]
    aux = np.zeros((4, layout.width))
    aux[:, depth] = [3.0, 2.0, 5.0, 7.0]
    aux[:, normal] = [1.0, 0.0, 0.5, 0.5]
    film.add(np.array([24, 24, 25, 25]), np.ones((4, 3)), aux)
    mean = film.aux_mean()
    assert mean.shape == (1, 2, layout.width) and film.counts.tolist() == [[2, 2]]
    assert mean[0, :, depth].tolist() == [2.0, 5.0]
    assert mean[0, :, normal].tolist() == [0.5, 0.5]
    empty = Film(10, 8, layout, region=(0, 0, 1, 1)).aux_mean()
    assert empty[0, 0, depth] == 1e10 and Film.bytes_per_pixel(layout) == 56 + 8 * layout.width
