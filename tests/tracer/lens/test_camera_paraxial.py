"""The compiled real-lens camera against first-order optics (the ABCD matrices of ``paraxial.py``).

Rays near the axis through the middle of the pupil obey paraxial optics (the residues,
spherical aberration and coma, shrink as the square of the ray's height in the pupil:
measured 5e-6 of the distance or less at 2 % of the pupil radius), so they must reproduce
the focal length, the conjugate image distance and the pupils; at a small stop the whole
bundle's irradiance at the film centre is that of the paraxial exit pupil (the residue
shrinks as 1/N^2).
"""

import math

import numpy as np
import pytest

from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.paraxial import image_distance_mm, paraxial_data

from .lens_cameras import D_LINE_NM, lattice_uv, lens_path, real_lens_camera, ring_uv


NEAR_AXIS = 0.02  # ray height in the pupil, as a fraction of the sampled shape's radius


def _stopped(name, fstop):
    return load_lens(lens_path(name)).with_fstop(fstop)


@pytest.mark.parametrize("name, wavelength_nm", [
    ("singlet_bk7_100mm", 450.0), ("singlet_bk7_100mm", D_LINE_NM), ("singlet_bk7_100mm", 650.0),
    ("double_gauss_50mm", 480.0),
])
def test_film_at_the_back_focus_sends_parallel_rays_at_the_focal_length_angle(name, wavelength_nm):
    """With the film in the rear focal plane, a film point at height h sends its rays out
    parallel at tan(theta) = h / EFL, the EFL of that wavelength."""
    paraxial = paraxial_data(_stopped(name, 16.0), wavelength_nm)
    camera = real_lens_camera(lens_path(name), 16.0, sensor_distance_mm=paraxial.bfl_mm)
    height_mm = 0.2
    uv = ring_uv(NEAR_AXIS)
    weight, _, direction = camera.camera_space_rays(np.tile([height_mm, 0.0], (len(uv), 1)), uv, wavelength_nm)
    assert (weight > 0).all()
    efl_mm = height_mm / (direction[:, 0] / direction[:, 2])
    np.testing.assert_allclose(efl_mm, paraxial.efl_mm, rtol=2e-5)
    assert abs(direction[:, 1].mean()) < 1e-12  # the ring is symmetric about the meridional plane


@pytest.mark.parametrize("name", ["singlet_bk7_100mm", "double_gauss_50mm"])
@pytest.mark.parametrize("object_z_mm", [-300.0, -1000.0])
def test_rays_from_the_film_centre_meet_at_the_paraxial_object_point(name, object_z_mm):
    """Film at the paraxial image distance of an axial object: the near-axis rays the camera
    traces from the film centre cross the axis at that object (lens coordinates)."""
    system = _stopped(name, 16.0)
    camera = real_lens_camera(lens_path(name), 16.0, sensor_distance_mm=image_distance_mm(system, object_z_mm))
    uv = ring_uv(NEAR_AXIS)
    weight, origin_m, direction = camera.camera_space_rays(np.zeros((len(uv), 2)), uv, D_LINE_NM)
    assert (weight > 0).all()
    along = -(origin_m[:, 0] * direction[:, 0] + origin_m[:, 1] * direction[:, 1]) / (
        direction[:, 0] ** 2 + direction[:, 1] ** 2)
    crossing_z_mm = (origin_m[:, 2] + along * direction[:, 2]) * 1000.0 + camera.film_z_mm
    np.testing.assert_allclose(crossing_z_mm, object_z_mm, rtol=1e-4)


@pytest.mark.parametrize("name", ["singlet_bk7_100mm", "double_gauss_50mm", "wide_angle_22mm", "telephoto_250mm"])
def test_centre_irradiance_is_the_projected_solid_angle_of_the_exit_pupil(name):
    """A disk of radius a seen on axis from distance d subtends the projected solid angle
    pi a^2 / (a^2 + d^2): at f/32 the camera's centre irradiance (what its weights are
    normalised by) is that of the paraxial exit pupil within 0.3 %."""
    system = _stopped(name, 32.0)
    paraxial = paraxial_data(system)
    camera = real_lens_camera(lens_path(name), 32.0, sensor_distance_mm=paraxial.bfl_mm)
    a = 0.5 * paraxial.exit_pupil_diameter_mm
    d = camera.film_z_mm - paraxial.exit_pupil_z_mm
    expected = math.pi * a * a / (a * a + d * d)
    assert camera.kernel_tables().centre_irradiance == pytest.approx(expected, rel=3e-3)


def test_chief_rays_pass_the_paraxial_pupil_centres():
    """From an off-axis film point, the centre of the bundle the stop lets through crosses the
    axis at the exit pupil on the film side (where the sampled rear-plane points aim) and at
    the entrance pupil on the scene side (where the traced rays leave)."""
    system = _stopped("double_gauss_50mm", 32.0)
    paraxial = paraxial_data(system)
    camera = real_lens_camera(lens_path("double_gauss_50mm"), 32.0, sensor_distance_mm=paraxial.bfl_mm)
    height_mm = 1.0
    uv = lattice_uv()
    film = np.tile([height_mm, 0.0], (len(uv), 1))
    weight, origin_m, direction = camera.camera_space_rays(film, uv, D_LINE_NM)
    passed = weight > 0
    assert passed.mean() > 0.5
    rear_points, _ = camera.pupil.sample(film, uv)
    rear_x = rear_points[passed, 0].mean()
    to_rear_mm = camera.film_z_mm - system.rear_z_mm
    exit_pupil_z = camera.film_z_mm - height_mm * to_rear_mm / (height_mm - rear_x)
    assert exit_pupil_z == pytest.approx(paraxial.exit_pupil_z_mm, abs=0.05)
    o, d = origin_m[passed], direction[passed]
    plane_z = o[:, 2].mean()
    x_at_plane = o[:, 0] + (plane_z - o[:, 2]) / d[:, 2] * d[:, 0]
    mean_d = d.mean(axis=0)
    entrance_z = (plane_z - x_at_plane.mean() * mean_d[2] / mean_d[0]) * 1000.0 + camera.film_z_mm
    assert entrance_z == pytest.approx(paraxial.entrance_pupil_z_mm, abs=0.05)
