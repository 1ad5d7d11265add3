"""Connecting a point to the camera (``stages.camera_connection``): the inverse of the camera stage's
rays, the importance of a pinhole, and the pixel drawn under the filter."""

import numpy as np
import pytest

from engine.tracer.cameras import make_camera
from engine.tracer.jit import kernel
from engine.tracer.scene import Camera
from engine.tracer.stages.camera import camera_ray
from engine.tracer.stages.camera_connection import connect_to_camera, filter_pick, filter_weight

from .lights.emission_checks import chi_square_p
from .tracer_scenes import look_at, settings


@kernel
def _connect_many(camera, points, u, pixel, lens, importance, times):
    for i in range(points.shape[0]):
        p = (points[i, 0], points[i, 1], points[i, 2])
        pixel[i], l, importance[i], _ = connect_to_camera(camera, p, (u[i, 0], u[i, 1]), (u[i, 2], u[i, 3]),
                                                          times[i])
        lens[i, 0], lens[i, 1], lens[i, 2] = l


@kernel
def _picks(camera, x, u, out):
    for i in range(u.shape[0]):
        out[i] = filter_pick(camera, x, camera.width, u[i])[0]


def _camera(model, moving=False, **kw):
    cam = Camera("cam", look_at((0.3, -2.0, 1.0), (0.0, 0.5, 0.4)), (40, 30), focal_length_mm=35.0,
                 film_width_mm=36.0, film_height_mm=27.0, model=model, fstop=0.8, focus_distance_m=2.5,
                 shift_x=0.05, shift_y=-0.1)
    if moving:  # motion blur: the camera slides 0.6 m and swings its aim 0.8 m during the shutter
        cam.shutter_times = np.array([0.0, 1.0])
        cam.motion_to_world = np.stack([look_at((0.3 + dx, -2.0, 1.0), (0.0 - 4 * dx / 3, 0.5, 0.4))
                                        for dx in (-0.3, 0.0, 0.3)])
    return make_camera(cam, settings(**kw)).data


@pytest.mark.parametrize("model, moving", [("pinhole", False), ("thin_lens", False), ("thin_lens", True)])
def test_points_on_camera_rays_connect_back_to_their_pixel_and_lens_point(model, moving):
    """A point on the camera ray through a raster position and lens point connects back to that pixel and lens
    point, with a pinhole's importance; a moving camera connects from where it stands at the ray's time."""
    camera = _camera(model, moving)
    rng = np.random.default_rng(0)
    n = 2000
    raster = rng.random((n, 2)) * (40, 30)
    lens_u = rng.random((n, 2))
    times = rng.random(n) if moving else np.full(n, 0.5)
    rays = [camera_ray(camera, x, y, u, v, t) for (x, y), (u, v), t in zip(raster, lens_u, times)]
    points = np.array([np.add(o, rng.uniform(0.5, 6.0) * np.asarray(d)) for o, d in rays])
    pixel, lens, importance = np.empty(n, np.int64), np.empty((n, 3)), np.empty(n)
    u = np.column_stack([lens_u, rng.random((n, 2))])
    _connect_many(camera, points, u, pixel, lens, importance, times)
    expected = np.floor(raster[:, 1]).astype(int) * 40 + np.floor(raster[:, 0]).astype(int)
    assert np.mean(pixel == expected) > 0.999  # (points on pixel edges may round either way)
    assert np.allclose(lens, [o for o, _ in rays], atol=1e-12)
    if moving:  # the frame's camera would put most of them elsewhere
        still = np.empty(n, np.int64)
        _connect_many(camera, points, u, still, lens.copy(), importance.copy(), np.full(n, 0.5))
        assert np.mean(still == expected) < 0.5
        return
    direction = np.array([d for _, d in rays])
    cos_theta = direction @ -camera.rotation[:, 2]
    assert np.allclose(importance, 40 * 30 / (camera.tan_w * camera.tan_h * cos_theta ** 3), rtol=1e-9)


def test_points_behind_the_camera_or_outside_the_frame_connect_to_no_pixel():
    camera = _camera("pinhole")
    eye = np.array([0.3, -2.0, 1.0])
    points = np.array([eye + (0, -1.0, 0), eye + (5.0, 0.3, 0), eye + (0, 0.1, 3.0)])
    pixel, lens, importance = np.empty(3, np.int64), np.empty((3, 3)), np.empty(3)
    _connect_many(camera, points - eye, np.full((3, 4), 0.5), pixel, lens, importance, np.full(3, 0.5))
    assert np.all(pixel < 0)


def test_gaussian_filter_picks_pixels_in_proportion_to_their_weight():
    camera = _camera("pinhole", pixel_filter="gaussian", filter_width_px=2.0)
    for x in (0.3, 7.61, 39.9):
        picks = np.empty(100_000, np.int64)
        _picks(camera, x, np.random.default_rng(1).random(100_000), picks)
        candidates = np.arange(40)
        weights = np.array([filter_weight(camera, x - (i + 0.5)) for i in candidates])
        assert set(np.unique(picks)) <= set(candidates[weights > 0])
        counts = np.bincount(picks, minlength=40)
        assert chi_square_p(counts[weights > 0], weights[weights > 0]) > 1e-3
        total = filter_pick(camera, x, 40, 0.5)[1]
        assert total == pytest.approx(weights.sum(), rel=1e-12)
    # far from the frame's edges the weights of a truncated Gaussian sum to about 1
    assert filter_pick(camera, 20.3, 40, 0.5)[1] == pytest.approx(1.0, abs=0.02)
    box = _camera("pinhole")
    assert filter_pick(box, 7.61, 40, 0.9) == (7, 1.0) and filter_pick(box, 40.2, 40, 0.5)[0] == -1
