"""Focusing on the real surfaces, and longitudinal chromatic aberration."""

import math

import numpy as np
import pytest

from engine.tracer.spectra.glass import glass_by_name
from engine.tracer.lens.catalogue import LENS_DIRECTORY
from engine.tracer.lens.focus import axial_bundle, best_focus, focus, focus_shift_mm, rms_spot_radius_mm
from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.paraxial import image_distance_mm

SINGLET = LENS_DIRECTORY / "singlet_bk7_100mm.lens"
ACHROMAT = LENS_DIRECTORY / "achromat_100mm.lens"


@pytest.mark.parametrize("lens_name, distance_mm", [("double_gauss_50mm", 2000.0), ("singlet_bk7_100mm", math.inf),
                                                    ("telephoto_250mm", 10000.0)])
def test_rms_spot_is_smallest_at_the_computed_sensor_distance(lens_name, distance_mm):
    lens = load_lens(LENS_DIRECTORY / f"{lens_name}.lens")
    result = focus(lens, distance_mm)
    origins, directions = axial_bundle(lens, result.object_z_mm)
    film = lens.rear_z_mm + result.sensor_distance_mm
    best = rms_spot_radius_mm(origins, directions, film)
    assert best == pytest.approx(result.rms_spot_mm, rel=1e-9)
    for delta in (0.002, 0.02, 0.2):
        assert rms_spot_radius_mm(origins, directions, film - delta) > best
        assert rms_spot_radius_mm(origins, directions, film + delta) > best
    # The spot's RMS^2 is a parabola in the film position: its vertex is the closed-form optimum.
    z = film + np.array([-0.5, 0.0, 0.5])
    rms2 = [rms_spot_radius_mm(origins, directions, zi) ** 2 for zi in z]
    vertex = film + 0.5 * 0.5 * (rms2[0] - rms2[2]) / (rms2[0] - 2 * rms2[1] + rms2[2])
    assert vertex == pytest.approx(film, abs=1e-5)
    # Spherical aberration moves best focus only a little from the paraxial focus.
    assert abs(result.sensor_distance_mm - result.paraxial_sensor_distance_mm) < 0.01 * lens.nominal_focal_length_mm


def test_singlet_paraxial_colour_follows_its_glass():
    """Plano-convex, curved side first: back focal length = R / (n - 1) - t / n, exactly."""
    lens = load_lens(SINGLET)
    bk7 = glass_by_name("N-BK7")
    for wavelength in (450.0, 486.13, 587.56, 650.0):
        n = float(bk7.index(wavelength))
        assert image_distance_mm(lens, -math.inf, wavelength) == pytest.approx(51.68 / (n - 1) - 4.0 / n, rel=1e-12)


def test_best_focus_of_blue_and_red_differ_as_paraxial_optics_predicts():
    singlet, achromat = load_lens(SINGLET), load_lens(ACHROMAT)
    shifts = {}
    for name, lens in (("singlet", singlet), ("achromat", achromat)):
        blue = best_focus(lens, -math.inf, 450.0).sensor_distance_mm
        red = best_focus(lens, -math.inf, 650.0).sensor_distance_mm
        shifts[name] = red - blue
        paraxial = focus_shift_mm(lens, math.inf, 450.0, 650.0)
        if name == "singlet":
            assert shifts[name] == pytest.approx(paraxial, rel=0.02)
    n450, n650 = (float(glass_by_name("N-BK7").index(w)) for w in (450.0, 650.0))
    closed_form = (51.68 / (n650 - 1) - 4.0 / n650) - (51.68 / (n450 - 1) - 4.0 / n450)
    assert shifts["singlet"] == pytest.approx(closed_form, rel=0.02)
    assert abs(shifts["achromat"]) < shifts["singlet"] / 10  # measured: -0.153 vs 2.041 mm
    # Designed achromat: F and C focus together.
    assert abs(focus_shift_mm(achromat)) < 1e-3 < 1.5 < focus_shift_mm(singlet)


def test_bundled_double_gauss_is_colour_corrected_unlike_the_singlet():
    """With the design's glasses the double Gauss is achromatised: its F-C focus shift is a small
    fraction of a simple lens's of about the same focal length (0.067 mm vs ~0.78 mm for f = 50 mm)."""
    double_gauss = load_lens(LENS_DIRECTORY / "double_gauss_50mm.lens")
    singlet = load_lens(LENS_DIRECTORY / "singlet_bk7_100mm.lens")
    shift_double_gauss = focus_shift_mm(double_gauss)
    shift_singlet_scaled = focus_shift_mm(singlet) * 50.0 / 100.0  # axial colour scales with focal length
    assert abs(shift_double_gauss) < 0.1
    assert abs(shift_double_gauss) < abs(shift_singlet_scaled) / 5


# Glass-map bounds used to choose the V_d of the bundled lenses whose sources give no glasses: lowest and
# highest V_d of the SCHOTT catalogue (2017) glasses with n_d within 0.015 of the element's (see the lens files).
GLASS_MAP_VD_BOUNDS = {
    1.517: (51.54, 76.98), 1.529: (51.54, 76.98), 1.54: (45.75, 76.98), 1.599: (38.03, 61.27),
    1.603: (38.03, 61.27), 1.613: (36.37, 63.39), 1.617: (36.37, 63.39), 1.62: (36.37, 63.39),
    1.639: (33.82, 60.1), 1.654: (33.82, 60.1), 1.673: (32.21, 55.2), 1.713: (29.23, 53.83),
    1.772: (25.68, 49.62), 1.805: (25.36, 46.5),
}


@pytest.mark.parametrize("lens_name", ["wide_angle_22mm", "telephoto_250mm", "fisheye_10mm"])
def test_lenses_with_prism_chosen_abbe_numbers_are_achromatised_with_real_glasses(lens_name):
    """V_d chosen within the glass map make the F-C focus shift a tiny fraction of the focal length
    (measured: 0.0002, 0.009, -0.002 mm for 22, 250, 10 mm; the nearest-n_d glasses gave 1.82, 2.77, -0.64 mm)."""
    lens = load_lens(LENS_DIRECTORY / f"{lens_name}.lens")
    focal_length = lens.nominal_focal_length_mm
    assert abs(focus_shift_mm(lens)) < 0.001 * focal_length
    glasses = [s.medium for s in lens.surfaces if not s.medium.is_air]
    assert len(glasses) >= 4
    for glass in glasses:
        lo, hi = GLASS_MAP_VD_BOUNDS[round(glass.n_d, 3)]
        assert lo <= glass.v_d <= hi, (glass.label, glass.n_d, glass.v_d)
