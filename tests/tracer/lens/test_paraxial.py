"""Paraxial optics against closed forms: thick-lens formula, dispersion, pupils, conjugates."""

import math

import numpy as np
import pytest

from engine.tracer.lens.media import AIR, D_LINE_NM, catalogue_medium, constant_medium
from engine.tracer.lens.paraxial import image_distance_mm, paraxial_data, sensor_distance_for_focus
from engine.tracer.lens.system import LensSystem, Surface


def _thick_lens(medium, r1=60.0, r2=-45.0, t=9.0, stop_gap=2.0, stop_d=12.0):
    return LensSystem((
        Surface(math.inf, stop_gap, stop_d, AIR, True),
        Surface(r1, t, 30.0, medium),
        Surface(r2, 0.0, 30.0, AIR),
    ), name="thick")


def _lensmaker(n, r1, r2, t):
    power = (n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * t / (n * r1 * r2))
    f = 1.0 / power
    return f, f * (1.0 - (n - 1.0) * t / (n * r1)), f * (1.0 + (n - 1.0) * t / (n * r2))


def _bk7():
    return catalogue_medium("N-BK7")


def test_thick_biconvex_matches_the_lensmaker_formula():
    bk7 = _bk7()
    for wavelength in (D_LINE_NM, 480.0, 650.0):
        n = float(bk7.index(np.array([wavelength]))[0])
        data = paraxial_data(_thick_lens(bk7), wavelength)
        efl, bfl, ffd = _lensmaker(n, 60.0, -45.0, 9.0)
        assert data.efl_mm == pytest.approx(efl, rel=1e-6)
        assert data.bfl_mm == pytest.approx(bfl, rel=1e-6)
        # front focal point ffd in front of the first lens vertex (which is at z = 2)
        assert data.ffl_mm == pytest.approx(2.0 - ffd, rel=1e-6)
        assert data.back_principal_z_mm == pytest.approx(11.0 + bfl - efl, rel=1e-9)


def test_singlet_focal_length_follows_dispersion():
    """For a thin lens f(lambda) (n(lambda) - 1) is constant."""
    bk7 = _bk7()
    thin = _thick_lens(bk7, r1=100.0, r2=-100.0, t=1e-4)
    wavelengths = np.array([420.0, 486.13, 550.0, 587.56, 656.27, 750.0])
    products = [paraxial_data(thin, w).efl_mm * (bk7.index(np.array([w]))[0] - 1.0) for w in wavelengths]
    np.testing.assert_allclose(products, 50.0, rtol=2e-6)


def test_pupils_of_a_stop_in_front_and_behind():
    glass = constant_medium(1.5)
    lens = _thick_lens(glass, stop_gap=5.0)
    data = paraxial_data(lens)
    assert data.entrance_pupil_z_mm == 0.0 and data.entrance_pupil_diameter_mm == 12.0
    assert data.f_number == pytest.approx(data.efl_mm / 12.0)
    # Exit pupil: image of the stop through the lens, by the thick-lens conjugate equation.
    efl = data.efl_mm
    stop_to_front_principal = data.front_principal_z_mm - 0.0
    image_from_back_principal = 1.0 / (1.0 / efl - 1.0 / stop_to_front_principal)
    assert data.exit_pupil_z_mm == pytest.approx(data.back_principal_z_mm + image_from_back_principal, rel=1e-9)
    magnification = image_from_back_principal / stop_to_front_principal
    assert data.exit_pupil_diameter_mm == pytest.approx(12.0 * abs(magnification), rel=1e-9)


def test_focus_distance_is_measured_from_the_film():
    lens = _thick_lens(constant_medium(1.5))
    data = paraxial_data(lens)
    s = sensor_distance_for_focus(lens, 1000.0)
    object_z = lens.rear_z_mm + s - 1000.0
    assert image_distance_mm(lens, object_z) == pytest.approx(s, rel=1e-12)
    # Newton's equation x x' = -f^2 about the focal points.
    x = object_z - data.ffl_mm
    x_image = s - data.bfl_mm
    assert x * x_image == pytest.approx(-data.efl_mm**2, rel=1e-9)
    assert sensor_distance_for_focus(lens, math.inf) == pytest.approx(data.bfl_mm)
