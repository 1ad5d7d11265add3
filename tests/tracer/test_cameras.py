"""Cameras: Blender's frustum, shift and orientation; thin-lens focus and aperture."""

import numpy as np
import pytest

from engine.tracer.cameras import make_camera
from engine.tracer.errors import PrismInputError
from engine.tracer.scene import Camera
from engine.tracer.stages.camera import PINHOLE, THIN_LENS

from .tracer_scenes import camera_rays, look_at, settings


def _cam(**kw):
    base = dict(name="c", camera_to_world=look_at((1, 2, 3), (1, 2, 0), up=(0, 1, 0)), resolution=(64, 32),
                focal_length_mm=50.0, film_width_mm=36.0, film_height_mm=18.0)
    base.update(kw)
    return Camera(**base)


def test_pinhole_frustum_orientation_and_shift():
    xy = np.array([[32.0, 16.0], [64.0, 16.0], [32.0, 0.0]])  # centre, right edge, top edge
    o, d = camera_rays(_cam(), xy)
    assert np.allclose(o, [1, 2, 3])
    assert np.allclose(d[0], [0, 0, -1])
    assert d[1][0] / -d[1][2] == pytest.approx(18.0 / 50.0)  # half film width / focal length, towards +X
    assert d[2][1] / -d[2][2] == pytest.approx(9.0 / 50.0)  # top row looks up (+Y here)
    _, ds = camera_rays(_cam(shift_x=0.1, shift_y=-0.2), xy[:1])
    assert ds[0][0] / -ds[0][2] == pytest.approx(0.1 * 36 / 50)
    assert ds[0][1] / -ds[0][2] == pytest.approx(-0.2 * 36 / 50)


def test_thin_lens_focuses_at_focus_distance():
    cam = _cam(model="thin_lens", fstop=2.0, focus_distance_m=2.5)
    aperture = make_camera(cam, settings()).data.aperture_radius_m
    assert aperture == pytest.approx(0.05 / 4)
    rng = np.random.default_rng(0)
    n = 1000
    xy = np.tile([[10.3, 20.7]], (n, 1))
    o, d = camera_rays(cam, xy, rng.random((n, 2)))
    assert np.allclose(np.linalg.norm(d, axis=1), 1)
    t = 2.5 / -d[:, 2]  # world -Z is the view axis here; the focus plane is z = 3 - 2.5
    p = o + t[:, None] * d
    assert np.allclose(p, p[0], atol=1e-9)
    radius = np.linalg.norm(o[:, :2] - [1, 2], axis=1)
    assert radius.max() <= aperture + 1e-12 and radius.max() > 0.9 * aperture


def test_factory_and_errors():
    assert make_camera(_cam(), settings()).data.kind == PINHOLE
    assert make_camera(_cam(model="thin_lens"), settings()).data.kind == THIN_LENS
    with pytest.raises(PrismInputError, match="'c'"):
        make_camera(_cam(model="fisheye"), settings())
    with pytest.raises(PrismInputError):
        make_camera(_cam(focal_length_mm=0.0), settings())


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_real_lens_camera_renders_a_uniform_sky_white_at_the_centre(mode):
    """The lens disperses (hero wavelength kept, rolled to column 0 for the camera and
    back): a white sky must stay white on average in both modes, with no NaN."""
    from engine.tracer.renderer import Renderer

    from .test_integrator import _white
    from .tracer_scenes import settings, sphere_under_sky

    scene = sphere_under_sky(size=8)
    scene.triangles = scene.triangles[:0]
    scene.triangle_material = scene.triangle_material[:0]
    scene.camera = Camera("cam", look_at((0, -4, 0), (0, 0, 0)), (8, 8), model="real_lens",
                          lens_file="lenses/double_gauss_50mm.lens", fstop=4.0, focus_distance_m=4.0,
                          film_width_mm=4.0, film_height_mm=4.0)
    s = settings(wavelength_mode=mode, samples=256, samples_per_pass=256)
    r = Renderer(scene, s)
    assert "real lens" in r.strategy and "hero-wavelength termination (lens)" in r.strategy
    r.render_pass()
    mean = r.image_rgb().astype(np.float64).mean((0, 1)) / _white(s)
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) / 64) / _white(s)
    assert np.all(np.abs(mean - 1.0) < 4 * stderr + 0.01), (mean, stderr)
    assert r.stats["nan_samples"] == 0
