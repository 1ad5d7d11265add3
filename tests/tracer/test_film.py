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


def test_pass_columns_are_averaged_and_regions_index_the_frame():
    from engine.tracer.pass_table import FilmLayout, PassRequest

    layout = FilmLayout(PassRequest(("Depth", "Normal")))
    film = Film(10, 8, layout, region=(4, 2, 7, 3))  # three pixels of a 10 x 8 frame: (4, 2) .. (6, 2)
    depth, normal = layout.columns["depth"][0], layout.columns["normal"][0]
    aux = np.zeros((5, layout.width))
    aux[:, depth] = [3.0, 0.0, 5.0, 7.0, 0.0]  # the second and fifth samples see no surface
    aux[:, depth + 1] = [1, 0, 1, 1, 0]
    aux[:, normal] = [1.0, 0.0, 0.5, 0.5, 0.0]
    film.add(np.array([24, 24, 25, 25, 26]), np.ones((5, 3)), aux)
    assert film.aux_mean().shape == (1, 3, layout.width) and film.counts.tolist() == [[2, 2, 1]]
    images = layout.images(film.aux_mean())
    assert images["Depth"][0, :, 0].tolist() == [3.0, 6.0, 1e10]  # a mean over the samples on a surface
    assert images["Normal"][0, :, 0].tolist() == [0.5, 0.5, 0.0]
    assert Film.bytes_per_pixel(layout) == 56 + 8 * layout.width
