"""The compiled camera ray as the render kernels use it: normalisation, unbiased pupil
bounds, placement, dead rays, and the same rays from a kernel loop as from ``generate_rays``."""

import math

import numba
import numpy as np
import pytest

from engine.tracer.lens.camera_kernel import camera_ray, film_point_mm

from .lens_cameras import D_LINE_NM, lens_path, real_lens_camera


@pytest.mark.parametrize("name, fstop", [
    ("double_gauss_50mm", 2.0), ("double_gauss_50mm", 8.0), ("singlet_bk7_100mm", 8.0),
    ("wide_angle_22mm", 4.0), ("telephoto_250mm", 5.6), ("fisheye_10mm", 4.0),
])
def test_a_uniform_white_scene_gives_weight_one_at_the_film_centre(name, fstop):
    """The mean weight is the irradiance a uniform radiance-1 scene gives, relative to the
    film centre's: 1 there at every f-stop (as Blender's cameras expose)."""
    camera = real_lens_camera(lens_path(name), fstop)
    n = 40000
    rng = np.random.default_rng(17)
    weight, _, _ = camera.camera_space_rays(np.zeros((n, 2)), rng.random((n, 2)), rng.uniform(380.0, 720.0, n))
    assert weight.mean() == pytest.approx(1.0, abs=4 * weight.std() / math.sqrt(n) + 0.002)


@pytest.mark.parametrize("film_radius_mm", [10.0, 18.0])
def test_pupil_bounds_change_the_noise_not_the_irradiance(film_radius_mm):
    bounded = real_lens_camera(lens_path("double_gauss_50mm"), 2.0)
    whole = real_lens_camera(lens_path("double_gauss_50mm"), 2.0, use_pupil_bounds=False)
    n = 40000
    rng = np.random.default_rng(int(film_radius_mm))
    film = np.tile([film_radius_mm * math.cos(0.4), film_radius_mm * math.sin(0.4)], (n, 1))
    w_bounded, _, _ = bounded.camera_space_rays(film, rng.random((n, 2)), D_LINE_NM)
    w_whole, _, _ = whole.camera_space_rays(film, rng.random((n, 2)), D_LINE_NM)
    se_bounded, se_whole = w_bounded.std() / math.sqrt(n), w_whole.std() / math.sqrt(n)
    assert w_bounded.mean() == pytest.approx(w_whole.mean(), abs=4 * math.hypot(se_bounded, se_whole))
    assert se_bounded < 0.7 * se_whole
    assert bounded.kernel_tables().centre_irradiance == pytest.approx(whole.kernel_tables().centre_irradiance,
                                                                       rel=3e-3)


@numba.njit
def _render_loop(tables, raster_xy, uv, wavelength_nm, out):
    for k in range(raster_xy.shape[0]):
        film_x, film_y = film_point_mm(tables, raster_xy[k, 0], raster_xy[k, 1])
        ray = camera_ray(tables, film_x, film_y, uv[k, 0], uv[k, 1], wavelength_nm[k])
        for j in range(7):
            out[k, j] = ray[j]


def test_a_kernel_loop_gets_the_rays_generate_rays_gives():
    camera = real_lens_camera(lens_path("double_gauss_50mm"), 2.8)
    rng = np.random.default_rng(2)
    n = 2000
    raster, uv, wavelength = rng.random((n, 2)) * 64, rng.random((n, 2)), rng.uniform(380.0, 720.0, n)
    out = np.empty((n, 7))
    _render_loop(camera.kernel_tables(), raster, uv, wavelength, out)
    origins, directions, weight = camera.generate_rays(raster, uv, np.column_stack([wavelength, wavelength]))
    np.testing.assert_array_equal(out[:, 0] * 2, weight[:, 0])  # K = 2 wavelengths: the hero carries 2x
    np.testing.assert_allclose(out[:, 1:4], origins, atol=1e-15)  # the camera sits at the world origin
    np.testing.assert_allclose(out[:, 4:7], directions, atol=1e-15)
    alive = out[:, 0] > 0
    assert 0.6 < alive.mean() < 1.0
    np.testing.assert_allclose(np.linalg.norm(out[alive, 4:7], axis=1), 1.0, atol=1e-14)


def test_rays_leave_the_front_element_in_camera_metres():
    """Lens coordinates map to camera space by x, y unchanged and Z = (z - film_z) / 1000: the
    rays start on the front surface's sphere, in front of the film (Z < 0), looking down -Z."""
    camera = real_lens_camera(lens_path("double_gauss_50mm"), 2.0)
    n = 3000
    rng = np.random.default_rng(4)
    film = rng.uniform(-12.0, 12.0, (n, 2))
    weight, origin_m, direction = camera.camera_space_rays(film, rng.random((n, 2)), D_LINE_NM)
    alive = weight > 0
    front = camera.system.surfaces[0]
    lens_mm = origin_m[alive] * 1000.0 + [0.0, 0.0, camera.film_z_mm]
    centre = np.array([0.0, 0.0, camera.system.vertex_z_mm[0] + front.radius_mm])
    np.testing.assert_allclose(np.linalg.norm(lens_mm - centre, axis=1), abs(front.radius_mm), rtol=1e-12)
    assert (direction[alive, 2] < 0).all()
    assert (np.hypot(lens_mm[:, 0], lens_mm[:, 1]) <= front.semi_aperture_mm + 1e-9).all()


def test_raster_positions_map_to_the_film_rotated_180_degrees():
    camera = real_lens_camera(lens_path("double_gauss_50mm"), 2.0, film_mm=24.0)
    tables = camera.kernel_tables()
    assert film_point_mm(tables, 32.0, 32.0) == (-0.0, -0.0)
    assert film_point_mm(tables, 0.0, 0.0) == (12.0, -12.0)  # top left of the image: lens +x, -y
    np.testing.assert_array_equal(camera.film_points_mm(np.array([[64.0, 64.0], [16.0, 48.0]])),
                                  [[-12.0, 12.0], [6.0, 6.0]])


def test_film_outside_the_image_circle_gets_dead_rays():
    camera = real_lens_camera(lens_path("double_gauss_50mm"), 8.0, film_mm=80.0)
    assert "outside the image circle" in camera.strategy
    tables = camera.kernel_tables()
    corner_x, corner_y = film_point_mm(tables, 0.5, 0.5)
    dead = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0)
    assert camera_ray(tables, corner_x, corner_y, 0.3, 0.7, 550.0) == dead
    assert camera_ray(tables, math.nan, 0.0, 0.3, 0.7, 550.0) == dead  # never a NaN ray
    assert camera_ray(tables, 0.0, 0.0, math.nan, 0.7, 550.0) == dead
    assert camera_ray(tables, 0.0, 0.0, 0.5, 0.5, 550.0)[0] > 0
