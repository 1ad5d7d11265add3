"""Exit-pupil sampling: the bounds never reject a ray that would pass, waste little, and
the radiometric weight gives the same irradiance as sampling the whole rear element."""

import numpy as np
import pytest

from engine.tracer.lens.catalogue import LENS_DIRECTORY
from engine.tracer.lens.exit_pupil import ExitPupilBounds
from engine.tracer.lens.focus import focus
from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.system import TOWARD_SCENE

FILM_RADIUS_MM = float(np.hypot(18.0, 12.0))


def _bounds(name, fstop=None, full=False):
    lens = load_lens(LENS_DIRECTORY / f"{name}.lens")
    if fstop:
        lens = lens.with_fstop(fstop)
    sensor = focus(lens, 3000.0, refine=False).sensor_distance_mm
    return lens, ExitPupilBounds(lens, lens.rear_z_mm + sensor, FILM_RADIUS_MM, full=full)


@pytest.mark.parametrize("name, fstop", [("double_gauss_50mm", 2.0), ("fisheye_10mm", None), ("wide_angle_22mm", None)])
def test_no_ray_outside_the_bounds_gets_through(name, fstop):
    lens, bounds = _bounds(name, fstop)
    rng = np.random.default_rng(7)
    count, grid = 24, 80
    radius = np.concatenate([[0.0, FILM_RADIUS_MM], rng.uniform(0, FILM_RADIUS_MM, count - 2)])
    radius[2:8] = (np.arange(6) * 9 + 1) * bounds.bin_width_mm - 1e-9  # just below bin edges
    angle = rng.uniform(0, 2 * np.pi, count)
    film_xy = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    u = np.linspace(-bounds.search_half_mm, bounds.search_half_mm, grid)
    gx, gy = (g.ravel() for g in np.meshgrid(u, u))
    film = np.repeat(film_xy, grid * grid, axis=0)
    rear = np.tile(np.column_stack([gx, gy]), (count, 1))
    wavelength = rng.uniform(380.0, 780.0, len(film))
    start = np.column_stack([film, np.full(len(film), bounds.film_z_mm)])
    target = np.column_stack([rear, np.full(len(film), bounds.rear_z_mm)])
    passes = lens.trace(start, target - start, wavelength, toward=TOWARD_SCENE).alive
    inside = bounds.contains(film, rear)
    assert passes.sum() > 300
    assert not (passes & ~inside).any(), f"{(passes & ~inside).sum()} passing rays fall outside the bounds"
    # The search square itself reaches beyond the rear element's clear aperture only by its sag.
    assert bounds.search_half_mm >= lens.rear_semi_aperture_mm


def _irradiance(lens, bounds, film_radius_mm, n, seed):
    """Monte Carlo estimate (and its standard error) of cos^4 A / z^2 at a film point on +x."""
    rng = np.random.default_rng(seed)
    film_xy = np.tile([film_radius_mm, 0.0], (n, 1))
    points, area = bounds.sample(film_xy, rng.random((n, 2)))
    start = np.column_stack([film_xy, np.full(n, bounds.film_z_mm)])
    d = points - start
    alive = lens.trace(start, d, 550.0, toward=TOWARD_SCENE).alive
    z = bounds.film_z_mm - bounds.rear_z_mm
    value = np.where(alive, (z / np.linalg.norm(d, axis=1)) ** 4 * area / z**2, 0.0)
    return value.mean(), value.std() / np.sqrt(n), 1.0 - alive.mean()


def test_bounded_sampling_is_unbiased_and_wastes_little():
    lens, bounded = _bounds("double_gauss_50mm", 2.0)
    _, whole = _bounds("double_gauss_50mm", 2.0, full=True)
    wasted = []
    for radius in (0.0, 10.0, 18.0):
        e_bounded, se_bounded, waste = _irradiance(lens, bounded, radius, 30000, 1)
        e_whole, se_whole, waste_whole = _irradiance(lens, whole, radius, 30000, 2)
        assert e_bounded == pytest.approx(e_whole, abs=4 * np.hypot(se_bounded, se_whole))
        assert se_bounded < se_whole  # the point of the bounds
        wasted.append(waste)
    # Measured (seeded): 16 % wasted at the centre, 19 % at 10 mm, 25 % at 18 mm for this f/2
    # double Gauss; sampling the whole rear element wastes 45 %, 63 % and 80 %.
    assert max(wasted) < 0.3 and waste_whole > 0.7
    # Vignetting: the off-axis irradiance falls (cos^4 and the cat's-eye pupil).
    centre = _irradiance(lens, bounded, 0.0, 20000, 3)[0]
    edge = _irradiance(lens, bounded, 20.0, 20000, 4)[0]
    assert edge < 0.7 * centre
