"""The compiled camera through an N-BK7 singlet whose rays have a closed form at every wavelength.

The singlet's film-side face is a sphere centred on the film centre, so every ray from the
film centre crosses it along the normal, unbent; the ray then meets the flat scene-side face
at the angle phi it left the film with, and leaves at sin(phi') = n(lambda) sin(phi), or is
totally reflected when n(lambda) sin(phi) > 1. n(lambda) is SCHOTT's Sellmeier formula for
N-BK7 with the catalogue's coefficients typed in here (not read from Prism's glass table).
"""

import math

import numpy as np
import pytest

from engine.tracer.lens.camera_kernel import camera_ray

from .lens_cameras import real_lens_camera

SCHOTT_N_BK7_B = (1.03961212, 0.231792344, 1.01046945)
SCHOTT_N_BK7_C_UM2 = (0.00600069867, 0.0200179144, 103.560653)

STOP_GAP_MM = 5.0  # stop (lens coordinates z = 0) to the flat face
GLASS_MM = 6.0  # flat face to the vertex of the spherical face
RADIUS_MM = 40.0  # the spherical face's radius: its centre is the film centre
FRONT_APERTURE_MM = 120.0
STOP_APERTURE_MM = 200.0
LENS = f"""
format = 1
name = "concentric N-BK7 test singlet"
f_number = 4.0

[[surface]]
stop = true
thickness_mm = {STOP_GAP_MM}
aperture_mm = {STOP_APERTURE_MM}

[[surface]]
radius_mm = inf
thickness_mm = {GLASS_MM}
aperture_mm = {FRONT_APERTURE_MM}
glass = "N-BK7"

[[surface]]
radius_mm = {RADIUS_MM}
thickness_mm = 0.0
aperture_mm = 76.0
"""


def _n_bk7(wavelength_nm):
    l2 = (wavelength_nm * 1e-3) ** 2
    return math.sqrt(1.0 + sum(b * l2 / (l2 - c) for b, c in zip(SCHOTT_N_BK7_B, SCHOTT_N_BK7_C_UM2)))


@pytest.fixture(scope="module")
def lens_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("lens") / "concentric.lens"
    path.write_text(LENS, encoding="utf-8")
    return str(path)


@pytest.fixture(scope="module")
def singlet(lens_file):
    """Sampling the exit-pupil bounds: nearly every ray passes."""
    return real_lens_camera(lens_file, 4.0, sensor_distance_mm=RADIUS_MM)


@pytest.fixture(scope="module")
def whole_rear(lens_file):
    """Sampling the whole rear element: rays beyond the critical angle too."""
    return real_lens_camera(lens_file, 4.0, sensor_distance_mm=RADIUS_MM, use_pupil_bounds=False)


def _rays(camera, wavelength_nm, n=6000, seed=11):
    """Camera rays from the film centre and the film-to-rear-plane angle phi each was launched at."""
    uv = np.random.default_rng(seed).random((n, 2))
    film = np.zeros((n, 2))
    weight, origin_m, direction = camera.camera_space_rays(film, uv, wavelength_nm)
    target, area = camera.pupil.sample(film, uv)
    phi = np.arctan(np.hypot(target[:, 0], target[:, 1]) / RADIUS_MM)
    azimuth = np.arctan2(target[:, 1], target[:, 0])
    return weight, origin_m, direction, phi, azimuth, area


@pytest.mark.parametrize("wavelength_nm", [404.66, 486.13, 587.56, 656.27, 706.52])
def test_rays_leave_at_the_snell_angle_of_their_wavelength(singlet, wavelength_nm):
    weight, origin_m, direction, phi, azimuth, _ = _rays(singlet, wavelength_nm)
    n = _n_bk7(wavelength_nm)
    alive = weight > 0
    assert alive.mean() > 0.8
    sin_out = n * np.sin(phi[alive])
    expected = np.column_stack([sin_out * np.cos(azimuth[alive]), sin_out * np.sin(azimuth[alive]),
                                -np.sqrt(1.0 - sin_out**2)])
    np.testing.assert_allclose(direction[alive], expected, atol=1e-12)
    # The ray leaves the stop plane (z = 0) at the height its two straight legs reach.
    film_z_mm = STOP_GAP_MM + GLASS_MM + RADIUS_MM
    height_mm = (film_z_mm - STOP_GAP_MM) * np.tan(phi[alive]) + STOP_GAP_MM * sin_out / np.sqrt(1.0 - sin_out**2)
    np.testing.assert_allclose(np.hypot(origin_m[alive, 0], origin_m[alive, 1]) * 1000.0, height_mm, rtol=1e-11)
    np.testing.assert_allclose(origin_m[alive, 2], -film_z_mm / 1000.0, atol=1e-15)


@pytest.mark.parametrize("wavelength_nm", [404.66, 706.52])
def test_total_internal_reflection_begins_at_the_critical_angle_of_each_wavelength(whole_rear, wavelength_nm):
    """Rays steeper than asin(1 / n(lambda)) die at the flat face (blue sooner than red);
    shallower ones pass with the weight cos^4(phi) A / z^2 / E_centre."""
    weight, _, _, phi, _, area = _rays(whole_rear, wavelength_nm, n=60000, seed=5)
    reaches_front = (RADIUS_MM + GLASS_MM) * np.tan(phi) < 0.5 * FRONT_APERTURE_MM
    snell = _n_bk7(wavelength_nm) * np.sin(phi)
    with np.errstate(invalid="ignore"):
        height_at_stop_mm = (RADIUS_MM + GLASS_MM) * np.tan(phi) + STOP_GAP_MM * snell / np.sqrt(1.0 - snell**2)
    clear = (np.abs(snell - 1.0) > 1e-9) & ~np.isclose(height_at_stop_mm, 0.5 * STOP_APERTURE_MM, rtol=1e-9)
    passes = reaches_front & (snell < 1.0) & (height_at_stop_mm < 0.5 * STOP_APERTURE_MM)
    assert passes.sum() > 1000 and (reaches_front & (snell > 1.0)).sum() > 1000
    np.testing.assert_array_equal((weight > 0)[clear], passes[clear])
    centre = whole_rear.kernel_tables().centre_irradiance
    expected = np.cos(phi) ** 4 * area / RADIUS_MM**2 / centre
    np.testing.assert_allclose(weight[passes], expected[passes], rtol=1e-12)


def test_the_kernel_disperses_as_the_sellmeier_ratio(singlet):
    """The same lens sample at two wavelengths: sin(phi') scales exactly as n(lambda)."""
    tables = singlet.kernel_tables()
    ray_blue = camera_ray(tables, 0.0, 0.0, 0.6, 0.55, 435.83)
    ray_red = camera_ray(tables, 0.0, 0.0, 0.6, 0.55, 643.85)
    assert ray_blue[0] > 0 and ray_red[0] > 0
    sin_blue, sin_red = math.hypot(ray_blue[4], ray_blue[5]), math.hypot(ray_red[4], ray_red[5])
    assert sin_blue / sin_red == pytest.approx(_n_bk7(435.83) / _n_bk7(643.85), rel=1e-12)
