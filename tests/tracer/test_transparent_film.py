"""Transparent film and holdouts (Cycles'): the background the camera sees has alpha 0 and brings no
light, surfaces alpha 1; a holdout is a transparent black hole for camera rays but still shadows and
reflects; transparent glass lets the background through by its transmittance."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from engine.tracer.visibility import ALL_RAYS, HOLDOUT

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _scene(sphere_material, world=None, flags=None):
    cam = Camera("cam", look_at((0, -4.0, 1.0), (0, 0, 0.5)), (24, 24), film_width_mm=24.0, film_height_mm=24.0)
    floor = quad((0, 0, 0), (1.0, 0, 0), (0, 1.0, 0))
    sphere = uv_sphere((0, 0, 0.6), 0.4, rings=12, segments=24)
    scene = make_scene([(*floor, 0), (*sphere, 1)], [Material("floor", base_color=(0.6, 0.6, 0.6)), sphere_material],
                       cam, [Light("sun", "sun", np.zeros(3), direction=np.array([0.3, 0.4, -1.0]), irradiance_w_m2=3.0)],
                       world or World(color=(0.2, 0.3, 0.5), strength=1.0))
    scene.triangle_object = np.concatenate([np.zeros(2, np.int32), np.ones(len(sphere[1]), np.int32)])
    scene.object_names = ["floor", "sphere"]
    if flags is not None:
        scene.object_flags = np.asarray(flags, np.uint8)
    return scene


def _render(scene, **kw):
    with Renderer(scene, settings(samples=16, samples_per_pass=16, **kw)) as r:
        r.render_pass()
        return r.image_rgb().astype(np.float64), r.image_alpha().astype(np.float64)


def test_transparent_film_background_is_alpha_zero_and_adds_no_light():
    scene = _scene(Material("red", base_color=(0.8, 0.1, 0.1)))
    opaque_rgb, opaque_alpha = _render(scene)
    rgb, alpha = _render(scene, film_transparent=True)
    assert np.all(opaque_alpha == 1.0)
    background = alpha == 0.0
    assert background.mean() > 0.2 and (alpha == 1.0).mean() > 0.2
    assert np.all(rgb[background] == 0.0)  # premultiplied: no background light
    assert np.all((alpha >= 0.0) & (alpha <= 1.0))  # edge pixels mix both
    # What the camera sees of the scene keeps its light (the sky still lights it).
    solid = alpha == 1.0
    assert np.allclose(rgb[solid], opaque_rgb[solid])


def test_holdout_is_a_transparent_hole_that_still_shadows_and_reflects():
    plain = _scene(Material("red", base_color=(0.8, 0.1, 0.1)))
    rgb, alpha = _render(plain)
    held = _scene(Material("red", base_color=(0.8, 0.1, 0.1)), flags=[ALL_RAYS, ALL_RAYS | HOLDOUT])
    held_rgb, held_alpha = _render(held)
    hole = held_alpha < 1.0
    assert 0.05 < hole.mean() < 0.5
    assert np.all(held_rgb[held_alpha == 0.0] == 0.0)
    # Elsewhere the image is unchanged: the sphere still shadows the floor and the film is opaque.
    assert np.allclose(held_rgb[~hole], rgb[~hole])
    # A Holdout material: the same hole, and black to indirect rays.
    shader = _scene(Material("hole", base_color=(0.0, 0.0, 0.0), holdout=True))
    shader_rgb, shader_alpha = _render(shader)
    assert np.array_equal(shader_alpha < 1.0, hole)


@pytest.mark.parametrize("glass_option", [False, True])
def test_transparent_glass_lets_the_background_through(glass_option):
    glass = Material("glass", kind="dielectric", ior=1.5)
    rgb, alpha = _render(_scene(glass), film_transparent=True, transparent_glass=glass_option)
    _, solid = _render(_scene(Material("m")), film_transparent=True)  # the same camera rays, opaque sphere
    sphere = solid == 1.0
    floor_or_sky = ~sphere
    centre = np.zeros_like(sphere)
    centre[8:12, 10:14] = True
    through_glass = centre & sphere
    assert through_glass.any()
    if glass_option:
        # Seen through clear glass the sky is transparent by the glass's transmittance (~0.9 at normal
        # incidence, two surfaces) where the ray reaches the sky; the floor seen through it stays opaque.
        assert alpha[through_glass].min() < 0.5
    else:
        assert np.all(alpha[sphere] == 1.0)
    assert floor_or_sky.any()
