"""RealLensCamera: orientation, focus, field of view, weights and errors."""

import math

import numpy as np
import pytest

from engine.tracer.errors import LensFileError, PrismInputError
from engine.tracer.lens.camera import RealLensCamera
from engine.tracer.lens.catalogue import LENS_DIRECTORY, field_of_view_deg
from engine.tracer.scene import Camera
from engine.tracer.settings import RenderSettings

W, H = 60, 40


def _camera(lens="double_gauss_50mm", transform=None, **kw):
    fields = dict(name="Cam", camera_to_world=np.eye(4) if transform is None else transform, resolution=(W, H),
                  model="real_lens", lens_file=str(LENS_DIRECTORY / f"{lens}.lens"), fstop=2.0, focus_distance_m=2.0)
    fields.update(kw)
    return Camera(**fields)


@pytest.fixture(scope="module")
def gauss():
    return RealLensCamera(_camera(), RenderSettings())


def _rays(cam, pixel, n=4000, k=3, seed=0, wavelength_nm=587.56):
    rng = np.random.default_rng(seed)
    pixel_xy = np.tile(np.asarray(pixel, dtype=float), (n, 1))
    return cam.generate_rays(pixel_xy, rng.random((n, 2)), np.full((n, k), wavelength_nm))


def test_image_is_upright_and_unmirrored(gauss):
    for pixel, axis, sign in (((5, H / 2), 0, -1), ((W - 5, H / 2), 0, 1), ((W / 2, 3), 1, 1), ((W / 2, H - 3), 1, -1)):
        o, d, w = _rays(gauss, pixel)
        alive = w[:, 0] > 0
        assert alive.mean() > 0.3
        assert np.sign(d[alive, axis].mean()) == sign, pixel
        assert (d[alive, 2] < 0).all()  # looking down -Z
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, atol=1e-12)


def test_rays_from_one_pixel_meet_at_the_focus_distance(gauss):
    o, d, w = _rays(gauss, (W / 2, H / 2))
    alive = w[:, 0] > 0

    def spread(z):
        t = (z - o[alive, 2]) / d[alive, 2]
        p = o[alive, :2] + t[:, None] * d[alive, :2]
        return np.sqrt(((p - p.mean(axis=0)) ** 2).sum(axis=1).mean())

    # Focused (d line) at 2 m from the film: the blur there is the lens's spherical
    # aberration seen through the magnification (0.013 mm RMS on the film x 38).
    z = -np.array([1.8, 1.9, 2.0, 2.1, 2.2])
    blur = [spread(zi) for zi in z]
    assert np.argmin(blur) == 2 and blur[2] < 0.0006  # metres
    assert spread(-1.0) > 5 * blur[2] and spread(-4.0) > 5 * blur[2]
    # The film is at the camera origin and the lens in front of it.
    assert (o[alive, 2] < -0.03).all() and (o[alive, 2] > -0.1).all()


def test_field_of_view_matches_the_traced_lens(gauss):
    o, d, w = _rays(gauss, (W, H / 2))  # right edge of the frame
    alive = w[:, 0] > 0
    mean = d[alive].mean(axis=0)
    half_angle = math.degrees(math.atan2(mean[0], -mean[2]))
    expected = field_of_view_deg(gauss.system, gauss.sensor_distance_mm, 36.0) / 2
    assert half_angle == pytest.approx(expected, abs=0.3)
    assert half_angle == pytest.approx(math.degrees(math.atan(18.0 / 50.34)), abs=1.0)


def test_weights_hero_column_only_and_unit_at_the_centre(gauss):
    o, d, w = _rays(gauss, (W / 2, H / 2), n=20000, k=4)
    assert (w[:, 1:] == 0).all()
    assert w[:, 0].mean() / 4 == pytest.approx(1.0, abs=0.03)
    assert (w[w[:, 0] > 0, 0] > 0).all() and np.isfinite(w).all()
    corner = _rays(gauss, (0.5, 0.5), n=20000, k=4)[2]
    assert corner[:, 0].mean() / 4 < 0.6  # vignetting and cos^4 at f/2
    assert 0.0 < gauss.wasted_fraction < 0.4 and "samples wasted" in gauss.strategy
    assert "Double Gauss 50mm" in gauss.strategy


def test_camera_transform_is_applied():
    turn = np.eye(4)
    turn[:3, :3] = [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]  # camera looks down world -X
    turn[:3, 3] = [1.0, 2.0, 3.0]
    cam = RealLensCamera(_camera("singlet_bk7_100mm", turn, fstop=8.0, focus_distance_m=5.0), RenderSettings())
    o, d, w = _rays(cam, (W / 2, H / 2), n=500)
    alive = w[:, 0] > 0
    assert (d[alive, 0] < -0.99).all()
    assert np.allclose(o[alive, 1:], [2.0, 3.0], atol=0.02) and (o[alive, 0] < 1.0).all()


def test_errors_name_the_camera_or_the_file(tmp_path):
    with pytest.raises(PrismInputError, match="Camera 'Cam' uses a real lens but no lens file"):
        RealLensCamera(_camera(lens_file=None), RenderSettings())
    with pytest.raises(LensFileError, match="does not exist"):
        RealLensCamera(_camera(lens_file=str(tmp_path / "x.lens")), RenderSettings())
    with pytest.raises(PrismInputError, match="closer than it can focus"):
        RealLensCamera(_camera("telephoto_250mm", focus_distance_m=0.2), RenderSettings())


def test_a_lens_glass_specified_on_part_of_the_visible_range_is_named_in_the_render_warnings():
    """The achromat's SF10 is specified from 380 nm; the render samples from 360 nm, where the kernels
    hold SF10's index at its 380 nm value: the render says so, once, naming lens and glass."""
    from benchmarks import scenes
    from engine.tracer.renderer import Renderer

    assert RealLensCamera(_camera(), RenderSettings()).warnings == []
    achromat = RealLensCamera(_camera("achromat_100mm", fstop=8.0), RenderSettings())
    assert achromat.warnings == ["Lens 'Achromatic doublet 100mm f/8': glass 'SF10' is specified for "
                                 "380-2500 nm only: wavelengths outside that range use its index at the nearer edge"]
    scene = scenes.build("cornell_grey")
    scene.camera = _camera("achromat_100mm", fstop=8.0, camera_to_world=scene.camera.camera_to_world,
                           resolution=(8, 8))
    renderer = Renderer(scene, RenderSettings(samples=1, threads=1))
    assert renderer.stats["warnings"] == achromat.warnings
