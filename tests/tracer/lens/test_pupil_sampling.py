"""Exit-pupil sampling (``pupil_sampling.sample_exit_pupil``): uniform in area over each bin's
shape, rotated to the film point's azimuth, with the shape's area (chi-square, fixed seeds)."""

import math

import numpy as np
import pytest
from scipy.stats import chisquare

from engine.tracer.lens.exit_pupil import ExitPupilBounds
from engine.tracer.lens.focus import focus
from engine.tracer.lens.lens_file import load_lens

from .lens_cameras import lens_path

FILM_RADIUS_MM = math.hypot(18.0, 12.0)
AZIMUTH = 2.2  # radians: a film point off both axes


@pytest.fixture(scope="module")
def gauss():
    lens = load_lens(lens_path("double_gauss_50mm")).with_fstop(2.0)
    film_z = lens.rear_z_mm + focus(lens, 3000.0, refine=False).sensor_distance_mm
    return ExitPupilBounds(lens, film_z, FILM_RADIUS_MM), ExitPupilBounds(lens, film_z, FILM_RADIUS_MM, full=True)


def _samples(bounds, film_radius_mm, n, seed):
    """Samples for one film point, turned back to the unrotated bin frame: (x, y, area, bin)."""
    film = np.tile([film_radius_mm * math.cos(AZIMUTH), film_radius_mm * math.sin(AZIMUTH)], (n, 1))
    points, area = bounds.sample(film, np.random.default_rng(seed).random((n, 2)))
    assert np.all(points[:, 2] == bounds.rear_z_mm)
    turn = AZIMUTH if film_radius_mm > 0 else 0.0  # the film centre has no azimuth: shapes unrotated
    c, s = math.cos(turn), math.sin(turn)
    x, y = c * points[:, 0] + s * points[:, 1], -s * points[:, 0] + c * points[:, 1]
    return x, y, area, int(bounds.bin_of(film[:1])[0])


@pytest.mark.parametrize("film_radius_mm", [0.0, 9.0, 19.5])
def test_ellipse_samples_are_uniform_in_area(gauss, film_radius_mm):
    bounds = gauss[0]
    n = 40000
    x, y, area, k = _samples(bounds, film_radius_mm, n, seed=int(film_radius_mm * 10) + 1)
    assert bounds.use_ellipse[k]  # round (or cat's-eye) pupils: the ellipse is the smaller shape
    cx, cy, sx, sy = bounds.ellipses[k]
    np.testing.assert_allclose(area, math.pi * sx * sy, rtol=1e-14)
    ex, ey = (x - cx) / sx, (y - cy) / sy
    rho2 = ex * ex + ey * ey
    assert rho2.max() <= 1.0 + 1e-12
    # 5 rings of equal area x 8 sectors: 40 cells of equal probability.
    ring = np.minimum((rho2 * 5).astype(int), 4)
    sector = np.minimum(((np.arctan2(ey, ex) + math.pi) / (2 * math.pi) * 8).astype(int), 7)
    counts = np.bincount(ring * 8 + sector, minlength=40)
    assert chisquare(counts).pvalue > 1e-3


@pytest.mark.parametrize("film_radius_mm", [0.0, 15.0])
def test_box_samples_are_uniform_in_area(gauss, film_radius_mm):
    bounds = gauss[1]
    n = 40000
    x, y, area, k = _samples(bounds, film_radius_mm, n, seed=int(film_radius_mm * 10) + 7)
    assert not bounds.use_ellipse[k]
    x0, x1, y0, y1 = bounds.boxes[k]
    np.testing.assert_allclose(area, (x1 - x0) * (y1 - y0), rtol=1e-14)
    u, v = (x - x0) / (x1 - x0), (y - y0) / (y1 - y0)
    assert u.min() >= -1e-12 and u.max() <= 1 + 1e-12 and v.min() >= -1e-12 and v.max() <= 1 + 1e-12
    cells = np.minimum((u * 8).astype(int), 7) * 8 + np.minimum((v * 8).astype(int), 7)
    assert chisquare(np.bincount(cells, minlength=64)).pvalue > 1e-3


def test_film_points_beyond_the_image_circle_draw_nothing():
    """An 80 mm square film behind the 50 mm double Gauss: its outer bins pass no ray, and
    their samples have area 0 (the camera gives them weight 0)."""
    lens = load_lens(lens_path("double_gauss_50mm")).with_fstop(8.0)
    film_z = lens.rear_z_mm + focus(lens, 3000.0, refine=False).sensor_distance_mm
    bounds = ExitPupilBounds(lens, film_z, math.hypot(40.0, 40.0))
    empty = ~np.any(bounds.boxes != 0.0, axis=1)
    assert empty[-1] and not empty[0] and not bounds.use_ellipse[empty].any()
    radius = (np.arange(len(empty)) + 0.5) * bounds.bin_width_mm
    film = np.column_stack([radius * math.cos(AZIMUTH), radius * math.sin(AZIMUTH)])
    _, area = bounds.sample(film, np.random.default_rng(3).random((len(film), 2)))
    np.testing.assert_array_equal(area == 0.0, empty)
