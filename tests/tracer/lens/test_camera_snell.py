"""The compiled camera through a plano-convex N-BK7 singlet, ray by ray against closed forms.

From the film point F each camera ray aims at its sample Q on the flat film-side face, so
its path is explicit: it refracts at that flat face (the tangential part of the direction
divides by n), crosses the glass in a straight line to the convex face (a quadratic), and
there either refracts (the tangential part multiplies by n; the normal part completes a
unit vector) or is totally reflected when n sin(i) > 1. n(lambda) is SCHOTT's Sellmeier
formula for N-BK7 with the catalogue coefficients typed in here, not Prism's glass table.
Every ray's fate, direction, exit point and weight must match at every wavelength.
"""

import numpy as np
import pytest

from .lens_cameras import real_lens_camera

SCHOTT_N_BK7_B = (1.03961212, 0.231792344, 1.01046945)
SCHOTT_N_BK7_C_UM2 = (0.00600069867, 0.0200179144, 103.560653)

STOP_RADIUS_MM = 30.0  # stop at z = 0
FRONT_Z_MM, FRONT_RADIUS_MM, CLEAR_RADIUS_MM = 2.0, 20.0, 18.0  # convex face, centre toward the film
REAR_Z_MM = 14.0  # flat face
SENSOR_DISTANCE_MM = 25.0
FILM_Z_MM = REAR_Z_MM + SENSOR_DISTANCE_MM
LENS = f"""
format = 1
name = "plano-convex N-BK7 test singlet"
f_number = 2.0

[[surface]]
stop = true
thickness_mm = {FRONT_Z_MM}
aperture_mm = {2 * STOP_RADIUS_MM}

[[surface]]
radius_mm = {FRONT_RADIUS_MM}
thickness_mm = {REAR_Z_MM - FRONT_Z_MM}
aperture_mm = {2 * CLEAR_RADIUS_MM}
glass = "N-BK7"

[[surface]]
radius_mm = inf
thickness_mm = 0.0
aperture_mm = {2 * CLEAR_RADIUS_MM}
"""
WAVELENGTHS_NM = (404.66, 486.13, 587.56, 656.27, 706.52)


def n_bk7(wavelength_nm):
    l2 = (wavelength_nm * 1e-3) ** 2
    return np.sqrt(1.0 + sum(b * l2 / (l2 - c) for b, c in zip(SCHOTT_N_BK7_B, SCHOTT_N_BK7_C_UM2)))


def _unit(v):
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def closed_form(film_xy_mm, target_mm, n):
    """(passes, direction out, exit point on the stop plane, incoming direction, TIR) per ray."""
    film = np.column_stack([film_xy_mm, np.full(len(film_xy_mm), FILM_Z_MM)])
    d0 = _unit(target_mm - film)
    d1_xy = d0[:, :2] / n
    d1 = np.column_stack([d1_xy, -np.sqrt(1.0 - (d1_xy**2).sum(axis=1))])
    centre = np.array([0.0, 0.0, FRONT_Z_MM + FRONT_RADIUS_MM])
    m = target_mm - centre  # the flat face lies inside the sphere: one exit root
    b = (m * d1).sum(axis=1)
    s = -b + np.sqrt(b * b - ((m * m).sum(axis=1) - FRONT_RADIUS_MM**2))
    p = target_mm + s[:, None] * d1
    normal = (p - centre) / FRONT_RADIUS_MM  # outward, along the ray
    cos_i = (d1 * normal).sum(axis=1)
    tangential = n * (d1 - cos_i[:, None] * normal)
    sin2_out = (tangential**2).sum(axis=1)
    tir = sin2_out > 1.0
    out = tangential + np.sqrt(np.clip(1.0 - sin2_out, 0.0, None))[:, None] * normal
    exit_mm = p + (-p[:, 2] / out[:, 2])[:, None] * out
    passes = ((np.hypot(target_mm[:, 0], target_mm[:, 1]) <= CLEAR_RADIUS_MM)
              & (np.hypot(p[:, 0], p[:, 1]) <= CLEAR_RADIUS_MM) & ~tir
              & (np.hypot(exit_mm[:, 0], exit_mm[:, 1]) <= STOP_RADIUS_MM))
    return passes, out, exit_mm, d0, tir


@pytest.fixture(scope="module")
def singlet(tmp_path_factory):
    path = tmp_path_factory.mktemp("lens") / "plano_convex.lens"
    path.write_text(LENS, encoding="utf-8")
    # The whole rear element is sampled, so steep rays that TIR are drawn too.
    return real_lens_camera(str(path), 2.0, sensor_distance_mm=SENSOR_DISTANCE_MM, use_pupil_bounds=False)


@pytest.mark.parametrize("film_xy_mm", [(0.0, 0.0), (6.0, -3.0)])
@pytest.mark.parametrize("wavelength_nm", WAVELENGTHS_NM)
def test_every_ray_follows_snell_at_its_wavelength(singlet, film_xy_mm, wavelength_nm):
    n = 20000
    uv = np.random.default_rng(int(wavelength_nm)).random((n, 2))
    film = np.tile(film_xy_mm, (n, 1))
    weight, origin_m, direction = singlet.camera_space_rays(film, uv, wavelength_nm)
    target, area = singlet.pupil.sample(film, uv)
    passes, out, exit_mm, d0, tir = closed_form(film, target, n_bk7(wavelength_nm))
    assert passes.sum() > 10000 and tir.sum() > 500
    boundary = np.isclose(np.hypot(exit_mm[:, 0], exit_mm[:, 1]), STOP_RADIUS_MM, rtol=1e-9)
    np.testing.assert_array_equal((weight > 0)[~boundary], passes[~boundary])
    np.testing.assert_allclose(direction[passes], out[passes], atol=1e-12)
    origin_mm = origin_m[passes] * 1000.0 + [0.0, 0.0, FILM_Z_MM]
    np.testing.assert_allclose(origin_mm, exit_mm[passes], atol=1e-10)
    # cos^4(theta) A / z^2 over the centre irradiance, theta measured from the film point
    expected = d0[passes, 2] ** 4 * area[passes] / SENSOR_DISTANCE_MM**2 / singlet.kernel_tables().centre_irradiance
    np.testing.assert_allclose(weight[passes], expected, rtol=1e-12)


def test_blue_is_totally_reflected_sooner_than_red(singlet):
    n = 20000
    uv = np.random.default_rng(1).random((n, 2))
    film = np.zeros((n, 2))
    passed = [(singlet.camera_space_rays(film, uv, w)[0] > 0).sum() for w in (404.66, 706.52)]
    target, _ = singlet.pupil.sample(film, uv)
    tir = [closed_form(film, target, n_bk7(w))[4].sum() for w in (404.66, 706.52)]
    assert tir[0] > tir[1] and passed[0] < passed[1]
    assert passed[1] - passed[0] == tir[0] - tir[1]  # the only fate that depends on lambda here
