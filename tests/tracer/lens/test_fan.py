"""Ray fans, fates, spot diagrams and outlines against closed forms."""

import math

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.lens.fan import PointSource, lens_diagram, pupil_grid_mm, pupil_range_mm, ray_fan, spot_diagrams
from engine.tracer.lens.media import AIR, FunctionMedium, constant_medium
from engine.tracer.lens.outline import element_outline, sag_mm, system_outlines
from engine.tracer.lens.ray_fate import FATE_ALIVE, FATE_BLOCKED, FATE_TIR
from engine.tracer.lens.system import LensSystem, Surface

WAVELENGTHS_NM = (450.0, 550.0, 650.0)


def cauchy_glass():
    """A dispersive glass: n(lambda) = 1.5046 + 4200 nm^2 / lambda^2 (about N-BK7)."""
    return FunctionMedium(lambda wl: 1.5046 + 4200.0 / wl**2, "cauchy")


def singlet(r1=100.0, r2=-100.0, thickness=2.0, aperture=10.0, glass=None, back=200.0):
    glass = glass or cauchy_glass()
    return LensSystem((Surface(r1, thickness, aperture, glass), Surface(r2, back, aperture, AIR)), name="singlet")


def thick_lens_bfd_mm(n, r1, r2, d):
    """Lensmaker's equation (thick lens) and the back focal distance from the rear vertex."""
    power = (n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2))
    f = 1.0 / power
    return f, f * (1.0 - (n - 1.0) * d / (n * r1))


def axis_crossing_z(fan):
    """z where each reached ray's last segment (rear surface -> sensor) crosses y = 0."""
    last = fan.vertex_count - 1
    rows = np.arange(len(last))
    a, b = fan.points_mm[rows, last - 1], fan.points_mm[rows, last]
    return a[:, 2] - a[:, 1] * (b[:, 2] - a[:, 2]) / (b[:, 1] - a[:, 1])


@pytest.mark.parametrize("wavelength_nm", WAVELENGTHS_NM)
def test_paraxial_rays_cross_the_axis_at_the_lensmaker_focus(wavelength_nm):
    glass = cauchy_glass()
    lens = singlet(glass=glass)
    heights = np.array([-1e-3, -5e-4, 5e-4, 1e-3])
    fan = ray_fan(lens, wavelength_nm, PointSource(), 0, sensor_z_mm=150.0, heights_mm=heights)
    assert np.all(fan.fate == FATE_ALIVE) and np.all(fan.fate_surface == -1)
    n = float(glass.index(np.array([wavelength_nm]))[0])
    f, bfd = thick_lens_bfd_mm(n, 100.0, -100.0, 2.0)
    np.testing.assert_allclose(axis_crossing_z(fan), lens.rear_z_mm + bfd, rtol=1e-7)
    # the thin-lens limit of the same equation is within the thickness correction
    assert abs(f - 1.0 / ((n - 1.0) * 2.0 / 100.0)) < 0.01 * f


def test_focal_length_grows_with_wavelength_in_normal_dispersion():
    lens = singlet()
    heights = np.array([1e-3])
    crossings = [axis_crossing_z(ray_fan(lens, w, PointSource(), 0, 150.0, heights))[0] for w in WAVELENGTHS_NM]
    assert crossings[0] < crossings[1] < crossings[2]


def test_fan_polylines_run_from_the_source_through_every_surface_to_the_sensor():
    lens = singlet()
    fan = ray_fan(lens, 550.0, PointSource(), 7, sensor_z_mm=120.0)
    assert fan.points_mm.shape == (7, 4, 3)  # start, two surfaces, sensor
    np.testing.assert_array_equal(fan.vertex_count, 4)
    np.testing.assert_allclose(fan.points_mm[:, -1, 2], 120.0)
    np.testing.assert_allclose(fan.points_mm[:, 1, 1], np.linspace(-5.0, 5.0, 7), atol=1e-9)  # spans the aperture
    assert np.all(np.diff(fan.points_mm[:, :, 2], axis=1) > 0)
    starts, ends, ray = fan.segments()
    assert len(starts) == 7 * 3 and np.all(np.bincount(ray) == 3)
    single = ray_fan(lens, 550.0, PointSource(), 1, sensor_z_mm=120.0)
    np.testing.assert_allclose(single.points_mm[0, :, 1], 0.0, atol=1e-12)  # one ray: along the axis


def test_rays_outside_a_clear_aperture_are_blocked_at_that_surface():
    glass = constant_medium(1.5)
    lens = LensSystem((Surface(100.0, 2.0, 10.0, glass), Surface(-100.0, 100.0, 6.0, AIR)))
    heights = np.array([0.0, 2.5, 4.0, 4.5, 6.0, -6.0])
    fan = ray_fan(lens, 550.0, PointSource(), 0, sensor_z_mm=150.0, heights_mm=heights)
    assert fan.fate_names() == [
        "sensor", "sensor", "blocked at surface 1", "blocked at surface 1", "blocked at surface 0",
        "blocked at surface 0",
    ]
    np.testing.assert_array_equal(fan.fate[2:], FATE_BLOCKED)
    np.testing.assert_array_equal(fan.vertex_count, [4, 4, 3, 3, 2, 2])  # blocked rays end on their surface
    blocked_at_1 = fan.points_mm[2, 2]
    assert np.hypot(*blocked_at_1[:2]) > 3.0 and abs(blocked_at_1[2] - (2.0 + sag_mm(-100.0, 4.0))) < 0.05
    np.testing.assert_array_equal(fan.points_mm[4, 2:], np.repeat(fan.points_mm[4, 1:2], 2, axis=0))


def test_total_internal_reflection_is_reported_at_its_surface():
    # Parallel rays inside n = 1.9 meet a sphere of radius 12 mm at asin(h / 12); the
    # critical angle is asin(1 / 1.9) = 31.8 deg, so h = 6 passes and h = 8 reflects.
    lens = LensSystem((Surface(math.inf, 10.0, 20.0, constant_medium(1.9)), Surface(-12.0, 30.0, 20.0, AIR)))
    fan = ray_fan(lens, 550.0, PointSource(), 0, sensor_z_mm=40.0, heights_mm=np.array([6.0, 8.0]))
    assert fan.fate.tolist() == [FATE_ALIVE, FATE_TIR]
    assert fan.fate_names()[1] == "TIR at surface 1"


def test_finite_source_rays_start_at_the_source_point():
    lens = singlet()
    source = PointSource(z_mm=-30.0, field_angle_deg=10.0)
    fan = ray_fan(lens, 550.0, source, 5, sensor_z_mm=300.0)
    expected = [0.0, 30.0 * math.tan(math.radians(10.0)), -30.0]
    np.testing.assert_allclose(fan.points_mm[:, 0], np.tile(expected, (5, 1)), atol=1e-9)


def test_window_spot_is_the_pupil_grid_and_its_rms():
    # A plane-parallel plate has no power: at normal incidence each ray lands where it was aimed.
    plate = LensSystem((Surface(math.inf, 5.0, 20.0, constant_medium(1.6)), Surface(math.inf, 10.0, 20.0, AIR)))
    (spot,) = spot_diagrams(plate, [550.0], PointSource(), sensor_z_mm=20.0, grid=21)
    span = pupil_range_mm(plate, PointSource(), 550.0, 20.0)
    assert span[0] == pytest.approx(-10.0, abs=0.05) and span[1] == pytest.approx(10.0, abs=0.05)
    aim = pupil_grid_mm(span, span, grid=21)
    inside = aim[np.hypot(aim[:, 0], aim[:, 1]) <= 10.0]
    assert spot.traced == len(aim)
    np.testing.assert_allclose(spot.hits_mm, inside, atol=1e-9)
    assert np.ptp(spot.hits_mm[:, 0]) > 15.0  # a 2D grid, not only the meridional fan
    assert spot.rms_radius_mm == pytest.approx(np.sqrt(np.mean(np.sum(inside**2, axis=1))), rel=1e-9)
    assert spot.rms_radius_mm == pytest.approx(10.0 / math.sqrt(2.0), rel=0.05)  # uniform disk


def test_spot_is_smallest_near_paraxial_focus_and_shows_axial_colour():
    lens = singlet(aperture=6.0)
    heights = np.array([1e-3])
    focus_550 = axis_crossing_z(ray_fan(lens, 550.0, PointSource(), 0, 150.0, heights))[0]
    at_focus = spot_diagrams(lens, WAVELENGTHS_NM, PointSource(), focus_550)
    defocused = spot_diagrams(lens, WAVELENGTHS_NM, PointSource(), focus_550 + 5.0)
    # 5 mm defocus at about f/16.6 blurs to a disk of diameter ~0.3 mm, RMS radius ~0.1 mm
    assert at_focus[1].rms_radius_mm < 0.03 and defocused[1].rms_radius_mm == pytest.approx(0.107, rel=0.15)
    assert at_focus[1].rms_radius_mm < at_focus[0].rms_radius_mm  # 450 nm focuses elsewhere


def test_element_outline_is_closed_and_follows_the_caps():
    outline = element_outline((0.0, 30.0, 10.0), (4.0, -50.0, 8.0))
    np.testing.assert_allclose(outline[0], outline[-1])
    front_rim = 30.0 - math.sqrt(30.0**2 - 10.0**2)
    assert outline[:, 1].max() == pytest.approx(10.0)
    assert np.isclose(outline[:, 0], front_rim).any()
    assert sag_mm(math.inf, 5.0) == 0.0


def test_lens_diagram_of_a_stopped_singlet():
    glass = cauchy_glass()
    stop = Surface(math.inf, 90.0, 6.0, AIR, is_stop=True)
    lens = LensSystem((Surface(100.0, 2.0, 10.0, glass), Surface(-100.0, 1.0, 10.0, AIR), stop), name="test")
    diagram = lens_diagram(lens, WAVELENGTHS_NM, n_rays=11, sensor_half_height_mm=5.0)
    assert [fan.wavelength_nm for fan in diagram.fans] == list(WAVELENGTHS_NM)
    # the fan spans the 10 mm front element; the 6 mm stop blocks the outer rays
    names = diagram.fans[1].fate_names()
    assert names[:2] == ["blocked at surface 2"] * 2 and names[-2:] == ["blocked at surface 2"] * 2
    assert diagram.fans[1].reached.sum() == 7
    assert len(diagram.outlines.elements) == 1 and len(diagram.outlines.stop) == 2
    # f-number: f / entrance pupil, the stop 1 mm behind the lens is imaged a little larger
    assert diagram.f_number == pytest.approx(lens_diagram_f_number(glass), rel=0.03)
    assert all(s.rms_radius_mm < 0.1 for s in diagram.spots)
    with pytest.raises(PrismInputError, match="inside"):
        lens_diagram(lens, WAVELENGTHS_NM, source_distance_mm=50.0)


def lens_diagram_f_number(glass):
    n = float(glass.index(np.array([587.5618]))[0])
    f, _ = thick_lens_bfd_mm(n, 100.0, -100.0, 2.0)
    return f / 6.0


def test_outlines_of_a_system_with_cemented_doublet():
    crown, flint = constant_medium(1.5), constant_medium(1.7)
    lens = LensSystem(
        (
            Surface(50.0, 4.0, 20.0, crown),
            Surface(-40.0, 2.0, 20.0, flint),
            Surface(-200.0, 5.0, 20.0, AIR),
            Surface(math.inf, 40.0, 8.0, AIR, is_stop=True),
        )
    )
    outlines = system_outlines(lens)
    assert len(outlines.elements) == 2  # crown and flint share the cemented surface
    upper, lower = outlines.stop
    assert upper[0, 1] == pytest.approx(4.0) and lower[0, 1] == pytest.approx(-4.0)
    assert upper[1, 1] >= 10.0  # reaches out to the neighbouring clear aperture
