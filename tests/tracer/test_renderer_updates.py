"""Changes between passes (what the viewport does): each ``set_*`` rebuilds only its own tables and
renders what a new Renderer of the changed scene renders."""

from dataclasses import replace

import numpy as np

from engine.tracer.renderer import REBASE_DISTANCE_M, Renderer
from engine.tracer.scene import Camera, Light, Material

from .tracer_scenes import look_at, make_scene, quad, settings


def _card_scene(card_colour=(0.8, 0.1, 0.1), light_at=(0.5, -0.5, 2.5), size=(24, 16)):
    """A grey floor, a coloured card above it and a point light, seen from the side and above."""
    camera = Camera("cam", look_at((0.0, -4.0, 3.0), (0.0, 0.0, 0.3)), size)
    floor = quad((0, 0, 0), (3, 0, 0), (0, 3, 0))
    card = quad((0, 0, 0.5), (0.6, 0, 0), (0, 0.6, 0))
    materials = [Material("floor", base_color=(0.5, 0.5, 0.5)), Material("card", base_color=card_colour)]
    light = Light("lamp", "point", np.array(light_at, dtype=np.float64), power_w=400.0)
    return make_scene([(*floor, 0), (*card, 1)], materials, camera, [light])


def _image(renderer, passes=1):
    for _ in range(passes):
        renderer.render_pass()
    return renderer.image_rgb()


def _fresh(scene, passes=1, **kw):
    with Renderer(scene, settings(**kw)) as r:
        return _image(r, passes)


def test_shading_change_keeps_the_embree_scene_and_renders_as_a_new_renderer():
    scene = _card_scene()
    green = _card_scene(card_colour=(0.1, 0.8, 0.1), light_at=(-0.5, 0.5, 2.0))
    with Renderer(scene, settings()) as r:
        _image(r)
        accel, geometry = r.tables.accel, r.tables.geometry
        r.set_shading(green)
        assert r.samples_done == 0 and r.film.counts.sum() == 0
        image = _image(r)
        assert r.tables.accel is accel and r.tables.geometry is geometry
    assert np.array_equal(image, _fresh(green))


def test_geometry_change_rebuilds_the_triangles():
    scene = _card_scene()
    parts = [(*quad((0, 0, 0), (3, 0, 0), (0, 3, 0)), 0), (*quad((0.8, 0, 0.5), (0.6, 0, 0), (0, 0.6, 0)), 1)]
    moved = make_scene(parts, scene.materials, scene.camera, scene.lights)
    with Renderer(scene, settings()) as r:
        before = _image(r)
        r.set_geometry(moved)
        after = _image(r)
    assert np.array_equal(after, _fresh(moved))
    assert not np.allclose(before, after)


def test_camera_move_keeps_the_origin_and_matches_a_new_renderer():
    scene = _card_scene()
    moved = replace(scene.camera, camera_to_world=look_at((1.5, -3.5, 2.5), (0.2, 0.0, 0.3)), resolution=(20, 20))
    with Renderer(scene, settings()) as r:
        origin, accel = r.origin.copy(), r.tables.accel
        _image(r)
        r.set_camera(moved, border=(2, 3, 18, 15))
        assert r.tables.accel is accel and np.array_equal(r.origin, origin)
        assert (r.width, r.height) == (20, 20) and r.samples_done == 0
        image = _image(r, passes=2)
        counts = r.film.counts
    # only the border is sampled
    assert counts[3:15, 2:18].min() == 8 and counts.sum() == 8 * 16 * 12
    reference = _fresh(replace(scene, camera=moved), passes=2, samples=8)
    # the same samples, geometry relative to another origin: float32 rounding only
    inside = image[3:15, 2:18]
    assert np.abs(inside - reference[3:15, 2:18]).mean() < 1e-3 * reference.mean()


def test_a_camera_far_from_the_origin_rebases_the_geometry():
    scene = _card_scene()
    far = replace(scene.camera, camera_to_world=look_at((0.0, -4.0 - 2 * REBASE_DISTANCE_M, 3.0), (0.0, 0.0, 0.3)))
    with Renderer(scene, settings()) as r:
        accel = r.tables.accel
        r.set_camera(far)
        assert r.tables.accel is not accel
        np.testing.assert_allclose(r.origin, far.camera_to_world[:3, 3])


def test_settings_change_and_restart_after_cancel():
    scene = _card_scene()
    with Renderer(scene, settings()) as r:
        r.cancel()
        r.render_pass()
        assert r.cancelled and r.samples_done == 0
        r.set_settings(settings(max_bounces=1, threads=1, seed=3))
        assert not r.cancelled
        image = _image(r)
    assert np.array_equal(image, _fresh(scene, max_bounces=1, threads=1, seed=3))
