"""Point clouds as spheres (``spheres``), rendered: a white furnace (albedo-1 spheres vanish under a uniform
sky, pixel for pixel), and a diffuse sphere lit by a point light and the sky against the same sphere as a
fine triangle mesh (absolute mean within its Monte Carlo error)."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from engine.tracer.spheres import SpherePoints

from .tracer_scenes import look_at, make_scene, settings, uv_sphere


def _points(centres, radii, material=0):
    centres = np.asarray(centres, np.float64).reshape(-1, 3)
    count = len(centres)
    return SpherePoints(centres, np.broadcast_to(np.asarray(radii, np.float64), (count,)).copy(),
                        np.full(count, material, np.int32), np.zeros(count, np.int32))


def _cloud(count=40, seed=4):
    rng = np.random.default_rng(seed)
    return _points(rng.uniform(-1.0, 1.0, (count, 3)), rng.uniform(0.05, 0.3, count))


def _camera(size):
    return Camera("cam", look_at((0, -4.0, 0.3), (0, 0, 0)), (size, size), film_width_mm=36.0, film_height_mm=36.0)


def test_white_furnace_of_points():
    """Albedo-1 spheres (overlapping, so paths also bounce between them) under a sky of radiance 1: every
    pixel equals the empty sky rendered with the same seed."""
    s = settings(samples=4, samples_per_pass=4, max_bounces=64)
    scene = make_scene([], [Material("white", base_color=(1.0, 1.0, 1.0))], _camera(24),
                       world=World(color=(1.0, 1.0, 1.0), strength=1.0))
    scene.points = _cloud()
    scene.object_names = ["Cloud"]
    r = Renderer(scene, s)
    r.render_pass()
    assert r.stats["nan_samples"] == 0
    image = r.image_rgb().astype(np.float64)
    scene.points = None
    sky = Renderer(scene, s)
    sky.render_pass()
    assert np.allclose(image, sky.image_rgb(), rtol=1e-5, atol=0)


def test_diffuse_sphere_point_matches_its_triangle_mesh():
    """One grey sphere as a point and as a 128 x 256 triangle mesh, lit by a point light and a dim sky: the
    same absolute mean (4 standard errors + the mesh's 0.03 % area deficit)."""
    s = settings(samples=64, samples_per_pass=64)
    light = Light("lamp", "point", np.array([2.0, -2.0, 3.0]), power_w=300.0)
    world = World(color=(0.1, 0.12, 0.15), strength=1.0)
    grey = [Material("grey", base_color=(0.6, 0.5, 0.4))]
    point = make_scene([], grey, _camera(32), [light], world)
    point.points = _points([[0.0, 0.0, 0.0]], 1.0)
    point.object_names = ["Cloud"]
    mesh = make_scene([(*uv_sphere((0, 0, 0), 1.0, rings=128, segments=256), 0)], grey, _camera(32), [light], world)
    means, errors = [], []
    for scene in (point, mesh):
        r = Renderer(scene, s)
        r.render_pass()
        assert r.stats["nan_samples"] == 0
        image = r.image_rgb().astype(np.float64)
        means.append(image.mean((0, 1)))
        errors.append(np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) / image[..., 0].size))
    difference = np.abs(means[0] - means[1])
    print(f"MEASURED point / mesh mean RGB {means[0] / means[1]}, standard error {np.hypot(*errors) / means[1]}")
    assert np.all(difference < 4 * np.hypot(*errors) + 3e-4 * means[1]), (means[0] / means[1], errors)


def test_light_tracing_aims_at_a_glass_point_as_at_a_glass_mesh():
    """A glass ball on a floor under an area light, as a sphere point and as a 64 x 128 triangle mesh, both
    with caustics by light tracing (On): the ball point is a caustic target as the mesh is,
    the light paths splat through it, and the images agree block by block (the caustic included)."""
    from .test_light_tracing import _blocks, _light_part, _render
    from .tracer_scenes import quad

    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)), Material("glass", kind="dielectric", ior=1.5)]
    light = Light("key", "area", np.array([0.3, 0.0, 2.5]), direction=np.array([-0.1, 0, -1.0]), power_w=1800.0,
                  size_u_m=2.0, size_v_m=2.0)
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), (32, 24), film_width_mm=36, film_height_mm=27)
    point = make_scene([(*floor, 0)], materials, cam, [light])
    point.points = _points([[0.0, 0.0, 0.5]], 0.5, material=1)
    point.object_names = ["Floor", "Ball"]
    point.points.object[:] = 1
    mesh = make_scene([(*floor, 0), (*uv_sphere((0, 0, 0.5), 0.5, rings=64, segments=128), 1)], materials, cam,
                      [light])
    renders = [_render(scene, samples=256, samples_per_pass=256, max_bounces=6, light_tracing="on", seed=3)
               for scene in (point, mesh)]
    for r in renders:
        assert "caustics by light tracing (glass)" in r.strategy and r.stats["light_splats"] > 10_000
        assert r.stats["nan_samples"] == 0
    a, b = (_blocks(r.image_rgb().astype(np.float64), 4).mean(-1) for r in renders)
    var = sum(_blocks(r.variance_rgb().astype(np.float64), 4).mean(-1) / 16 for r in renders)
    z = (a - b) / np.sqrt(var + 1e-12)
    caustic = _blocks(_light_part(renders[1]), 4).mean(-1) > 0.25 * b
    assert caustic.sum() >= 2
    assert np.all(np.abs(z) < 4.5), z
    assert abs(a[caustic].sum() - b[caustic].sum()) < 3.5 * np.sqrt(var[caustic].sum())


def test_points_hidden_from_camera_rays_leave_the_sky():
    """Object ▸ Visibility ▸ Camera off for a cloud of dark spheres, the scene's only object: camera rays pass
    through them (one Embree scene per kind of ray, spheres included; the camera rays' scene is empty), so the
    image is the empty sky."""
    from engine.tracer.visibility import ALL_RAYS, RAY_CAMERA

    s = settings(samples=4, samples_per_pass=4)
    scene = make_scene([], [Material("dark", base_color=(0.2, 0.2, 0.2))], _camera(24),
                       world=World(color=(1.0, 1.0, 1.0), strength=1.0))
    scene.points = _cloud()
    scene.object_names = ["Cloud"]
    scene.object_flags = np.array([ALL_RAYS & ~RAY_CAMERA], np.uint8)
    hidden = Renderer(scene, s)
    hidden.render_pass()
    assert hidden.tables.ray_classes is not None
    scene.points = None
    sky = Renderer(scene, s)
    sky.render_pass()
    assert np.array_equal(hidden.image_rgb(), sky.image_rgb())


def test_a_point_outside_a_lights_blocker_sets_casts_none_of_its_shadow():
    """Shadow linking reads a sphere hit's object: a ball point (blocker set 1) 1.5 m under the left light of
    ``test_light_linking``'s two floor halves shades the floor under it; outside the left light's blocker sets
    (set 0 only) it casts none of that light's shadow."""
    from .test_light_linking import _links, _render, _two_halves

    def with_ball(links=None):
        scene = _two_halves(card=False)
        scene.points = _points([[-1.0, 0.0, 1.5]], 0.25)
        scene.points.object[:] = 2
        scene.object_names = ["Left", "Right", "Ball"]
        scene.light_links = links
        return scene

    free, _ = _render(_two_halves(card=False))
    shadowed, _ = _render(with_ball())
    linked, r = _render(with_ball(_links(3, blockers=[(2, 1)], shadow_sets={"left": 0b1})))
    assert r.tables.kernel_settings.shadow_linking
    spot = (slice(6, 10), slice(5, 9))
    assert shadowed[spot].mean() < 0.7 * free[spot].mean()
    np.testing.assert_allclose(linked[spot].mean(), free[spot].mean(), rtol=0.02)


def test_point_info_reads_a_moving_points_centre_at_the_rays_time_and_its_radius_at_the_frame():
    """Cycles' Point Info on a moving point (``hit_inputs.point_info``): Position where the point stands at the
    ray's time (linear between the shutter's steps, as Cycles' ``point_position`` interpolates it), the frame's
    at ``FRAME_TIME``; Radius the frame's, as Cycles' ``point_radius`` reads it; zeros on the triangle row."""
    from collections import namedtuple

    from engine.tracer.geometry import FRAME_TIME
    from engine.tracer.materials.hit_inputs import point_info

    Tables = namedtuple("Tables", "triangles spheres sphere_motion sphere_random")
    motion = np.array([[[0.0, 0.0, 1.0, 0.1]], [[0.5, 0.0, 1.0, 0.2]], [[1.5, 0.0, 1.0, 0.4]]], np.float32)
    tables = Tables(np.zeros((1, 3), np.int32), motion[1], motion, np.array([0.25], np.float32))
    for time, x in ((0.0, 0.0), (0.25, 0.25), (0.5, 0.5), (0.75, 1.0), (1.0, 1.5), (FRAME_TIME, 0.5)):
        assert point_info(tables, 1, 0, time) == pytest.approx((x, 0.0, 1.0)), time
    assert point_info(tables, 1, 1, 0.9)[0] == pytest.approx(0.2)
    assert point_info(tables, 1, 2, 0.9)[0] == pytest.approx(0.25)
    assert point_info(tables, 0, 0, 0.5) == (0.0, 0.0, 0.0)
