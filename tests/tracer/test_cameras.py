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


def test_orthographic_rays_are_parallel_and_span_the_view():
    cam = _cam(projection="orthographic", ortho_width_m=4.0, ortho_height_m=2.0, shift_x=0.25)
    xy = np.array([[32.0, 16.0], [64.0, 16.0], [0.0, 0.0], [10.5, 30.25]])
    o, d = camera_rays(cam, xy)
    assert np.allclose(d, [0, 0, -1])
    # The camera sits at (1, 2, 3) looking down -Z with +Y up; the shift is in units of the larger side.
    assert np.allclose(o[0], [1 + 0.25 * 4.0, 2, 3])
    assert np.allclose(o[1] - o[0], [2.0, 0, 0]) and np.allclose(o[2] - o[0], [-2.0, 1.0, 0])


def test_orthographic_keeps_an_objects_size_as_it_moves_away():
    """A 1 m square seen by a 4 m wide orthographic camera covers a quarter of the width at any distance."""
    from engine.tracer.renderer import Renderer
    from engine.tracer.scene import Material, SpectrumSpec

    from .tracer_scenes import make_scene, quad

    widths = []
    for distance in (2.0, 9.0):
        cam = Camera("c", look_at((0, -distance, 0), (0, 0, 0)), (64, 64), projection="orthographic",
                     ortho_width_m=4.0, ortho_height_m=4.0)
        square = quad((0.3, 0, 0.2), (0.5, 0, 0), (0, 0, 0.5))
        glow = Material("glow", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=1.0)
        with Renderer(make_scene([(*square, 0)], [glow], cam), settings(samples=4, samples_per_pass=4)) as r:
            r.render_pass()
            lit = r.image_rgb()[..., 1] > 0.5
        widths.append((lit.any(axis=0).sum(), lit.any(axis=1).sum(), np.argwhere(lit).mean(axis=0)))
    assert widths[0][0] == widths[1][0] == 16 and widths[0][1] == widths[1][1] == 16
    assert np.allclose(widths[0][2], widths[1][2])  # and stays where it was


def test_equirectangular_directions_are_cycles_longitudes_and_latitudes():
    cam = _cam(projection="equirectangular", camera_to_world=look_at((0, 0, 0), (1, 0, 0)), resolution=(64, 32))
    xy = np.array([[32.0, 16.0], [16.0, 16.0], [48.0, 16.0], [32.0, 0.0], [0.0, 16.0], [40.0, 8.0]])
    _, d = camera_rays(cam, xy)
    # Looking along +X (up +Z): the image centre is +X, u = 1/4 is 90° to the left (+Y), u = 3/4 to the
    # right (-Y), the top row the zenith, the left edge straight behind.
    assert np.allclose(d[:5], [[1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [-1, 0, 0]], atol=1e-12)
    longitude, latitude = np.radians(45.0), np.radians(45.0)
    assert np.allclose(d[5], [np.cos(latitude) * np.cos(longitude), -np.cos(latitude) * np.sin(longitude),
                              np.sin(latitude)])
    narrow = _cam(projection="equirectangular", camera_to_world=look_at((0, 0, 0), (1, 0, 0)), resolution=(64, 32),
                  longitude_min_rad=-0.5, longitude_max_rad=1.5, latitude_min_rad=-0.2, latitude_max_rad=0.6)
    _, d = camera_rays(narrow, np.array([[0.0, 32.0], [64.0, 0.0]]))
    assert np.allclose(d[0], [np.cos(-0.2) * np.cos(-0.5), np.cos(-0.2) * np.sin(0.5), np.sin(-0.2)])
    assert np.allclose(d[1], [np.cos(0.6) * np.cos(1.5), -np.cos(0.6) * np.sin(1.5), np.sin(0.6)])


@pytest.mark.parametrize("kind", ["fisheye_equidistant", "fisheye_equisolid"])
def test_fisheye_angle_from_the_axis_follows_its_mapping(kind):
    fov = np.radians(200.0)
    cam = _cam(projection=kind, camera_to_world=look_at((0, 0, 0), (1, 0, 0)), resolution=(64, 64),
               film_width_mm=24.0, film_height_mm=24.0, fisheye_fov_rad=fov, fisheye_lens_mm=6.0)
    r_px = np.linspace(0.0, 31.9, 40)
    xy = np.stack([32.0 + r_px, np.full_like(r_px, 32.0)], axis=1)
    o, d = camera_rays(cam, xy)
    seen = np.linalg.norm(d, axis=1) > 0
    theta = np.arccos(np.clip(d[seen, 0], -1, 1))
    if kind == "fisheye_equidistant":
        expected = (r_px / 32.0) * fov / 2  # the circle fills the image
        assert seen.all()
    else:
        r_mm = r_px / 64.0 * 24.0
        expected = 2 * np.arcsin(r_mm / (2 * 6.0))
        assert np.array_equal(seen, r_mm <= 2 * 6.0 * np.sin(fov / 4))
        expected = expected[seen]
    assert np.allclose(theta, expected, atol=1e-9)
    assert np.all(d[seen][1:, 1] < 0)  # to the right of a camera looking along +X is -Y
    assert not (np.linalg.norm(camera_rays(cam, np.array([[0.2, 0.2]]))[1], axis=1) > 0).any()  # a corner


def _polygon_area(corners):
    return 0.5 * corners * np.sin(2 * np.pi / corners)


@pytest.mark.parametrize("blades", [5, 6])
def test_polygonal_aperture_is_uniform_over_its_polygon(blades):
    """Chi-square of aperture samples on a grid over the polygon (cells' expected mass from their area
    inside the polygon); the corners sit at rotation + (2k + 1)π/blades."""
    from scipy import stats

    from engine.tracer.warps import regular_polygon

    rotation = 0.3
    rng = np.random.default_rng(11)
    u = rng.random((100_000, 2))
    points = np.array([regular_polygon(a, b, blades, rotation) for a, b in u])
    angles = rotation + (2 * np.arange(blades) + 1) * np.pi / blades
    normals = np.stack([np.cos(angles[:-1] + np.pi / blades), np.sin(angles[:-1] + np.pi / blades)], 1)
    apothem = np.cos(np.pi / blades)
    inside = lambda p: (p @ np.stack([np.cos(rotation + 2 * np.pi * np.arange(blades) / blades + 2 * np.pi / blades),  # noqa: E731
                                      np.sin(rotation + 2 * np.pi * np.arange(blades) / blades + 2 * np.pi / blades)],
                                     1).T <= apothem + 1e-12).all(axis=1)
    assert inside(points).all() and normals.shape == (blades - 1, 2)
    bins = 12
    edges = np.linspace(-1, 1, bins + 1)
    observed, _, _ = np.histogram2d(points[:, 0], points[:, 1], [edges, edges])
    fine = (np.arange(bins * 20) + 0.5) / (bins * 20) * 2 - 1
    fx, fy = np.meshgrid(fine, fine, indexing="ij")
    mass = inside(np.stack([fx.ravel(), fy.ravel()], 1)).reshape(bins, 20, bins, 20).sum(axis=(1, 3)).astype(float)
    expected = mass / mass.sum() * len(points)
    keep = expected > 5
    chi2 = ((observed[keep] - expected[keep]) ** 2 / expected[keep]).sum()
    assert stats.chi2.sf(chi2, keep.sum() - 1) > 1e-3
    assert observed[mass == 0].sum() == 0
    assert np.mean((points**2).sum(1)) == pytest.approx(
        (1 + 2 * np.cos(np.pi / blades) ** 2) / 6, rel=0.01)  # second moment of the regular polygon


def test_thin_lens_circle_of_confusion_is_the_closed_form():
    """A small emitter off the focus plane spreads over a disc of radius R |1/z - 1/F| (tan units) on the
    film: R = f / 2N the aperture radius, z its depth, F the focus distance (Cycles' thin lens). Measured
    by the blur's second moment (ρ²/2 for a uniform disc of radius ρ)."""
    from engine.tracer.renderer import Renderer
    from engine.tracer.scene import Material, SpectrumSpec

    from .tracer_scenes import make_scene, quad

    focal, fstop, focus, depth, width = 50.0, 1.0, 0.5, 6.0, 96
    cam = Camera("c", look_at((0, 0, 0), (0, 1, 0)), (width, width), focal_length_mm=focal, film_width_mm=36.0,
                 film_height_mm=36.0, model="thin_lens", fstop=fstop, focus_distance_m=focus)
    dot = quad((0, depth, 0), (0.1, 0, 0), (0, 0, 0.1))
    glow = Material("glow", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=1.0)
    with Renderer(make_scene([(*dot, 0)], [glow], cam), settings(samples=256, samples_per_pass=256)) as r:
        r.render_pass()
        image = r.image_rgb()[..., 1].astype(np.float64)
    ys, xs = np.mgrid[0:width, 0:width] + 0.5
    total = image.sum()
    cx, cy = (image * xs).sum() / total, (image * ys).sum() / total
    second = (image * ((xs - cx) ** 2 + (ys - cy) ** 2)).sum() / total
    radius_m = focal / (2 * fstop) / 1000
    rho_px = radius_m * abs(1 / depth - 1 / focus) / (36.0 / focal) * width
    # The emitter's own image (20 cm at 6 m) and the pixels (box filter) add their second moments: a
    # square of side s has s²/6.
    side_px = 0.2 / depth / (36.0 / focal) * width
    assert rho_px > 5
    assert second == pytest.approx(rho_px**2 / 2 + side_px**2 / 6 + 1 / 6, rel=0.02)
    assert abs(cx - width / 2) < 0.05 and abs(cy - width / 2) < 0.05
