"""Object ray visibility (Cycles' Object ▸ Visibility ▸ Ray Visibility): an object hidden from camera
rays is not seen but still shadows; hidden from shadow rays it casts no shadow; hidden from glossy rays
it vanishes from mirrors; each exactly where the kind of ray says."""

import numpy as np

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from engine.tracer.visibility import ALL_RAYS, RAY_CAMERA, RAY_GLOSSY, RAY_SHADOW

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _scene(floor_material, sphere_flags, sphere=True):
    cam = Camera("cam", look_at((0, -4.0, 2.0), (0, 0, 0.3)), (24, 24), film_width_mm=24.0, film_height_mm=24.0)
    floor = quad((0, 0, 0), (2.0, 0, 0), (0, 2.0, 0))
    ball = uv_sphere((0, 0, 0.6), 0.5, rings=12, segments=24)
    parts = [(*floor, 0), (*ball, 1)] if sphere else [(*floor, 0)]
    scene = make_scene(parts, [floor_material, Material("black", base_color=(0.0, 0.0, 0.0))], cam,
                       [Light("sun", "sun", np.zeros(3), direction=np.array([0.0, 0.3, -1.0]), irradiance_w_m2=3.0)],
                       World(color=(0.1, 0.2, 0.4), strength=1.0))
    if sphere:
        scene.triangle_object = np.concatenate([np.zeros(2, np.int32), np.ones(len(ball[1]), np.int32)])
        scene.object_flags = np.array([ALL_RAYS, sphere_flags], np.uint8)
    return scene


def _render(scene):
    with Renderer(scene, settings(samples=16, samples_per_pass=16)) as r:
        r.render_pass()
        return r.image_rgb().astype(np.float64), r


def _silhouette():
    """Pixels where some camera ray meets the sphere: the same camera rays seeing a glowing sphere alone."""
    from engine.tracer.scene import SpectrumSpec

    scene = _scene(Material("black", base_color=(0.0, 0.0, 0.0)), ALL_RAYS)
    scene.lights, scene.world = [], World(color=(0.0, 0.0, 0.0), strength=0.0)
    scene.materials[1] = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    image, _ = _render(scene)
    return image.sum(-1) > 0


def test_hidden_from_camera_is_unseen_but_still_shadows():
    grey = Material("floor", base_color=(0.5, 0.5, 0.5))
    seen, _ = _render(_scene(grey, ALL_RAYS))
    hidden, r = _render(_scene(grey, ALL_RAYS & ~RAY_CAMERA))
    assert r.tables.ray_classes is not None
    empty, _ = _render(_scene(grey, 0, sphere=False))
    silhouette = _silhouette()
    shadow = silhouette & (np.abs(hidden - empty).sum(-1) > 0.05)
    assert silhouette.mean() > 0.1
    # Where the sphere is not in front of the camera the images are identical (the same camera rays).
    unchanged = ~silhouette
    assert np.array_equal(hidden[unchanged], seen[unchanged])
    # Where it was, the floor shows, with the sphere's shadow on it.
    assert shadow.any() and np.all(hidden[shadow].sum(-1) < empty[shadow].sum(-1))


def test_hidden_from_shadow_rays_casts_no_shadow():
    grey = Material("floor", base_color=(0.5, 0.5, 0.5))
    empty, _ = _render(_scene(grey, 0, sphere=False))
    # Hidden from the camera in both, so every pixel shows the floor.
    shadowed, _ = _render(_scene(grey, ALL_RAYS & ~RAY_CAMERA))
    unshadowed, _ = _render(_scene(grey, ALL_RAYS & ~RAY_CAMERA & ~RAY_SHADOW))
    floor_shadow = shadowed.sum(-1) < 0.6 * empty.sum(-1)
    assert floor_shadow.mean() > 0.02
    # The black sphere reflects nothing: without its shadow the floor there gets the sun as if it were
    # gone; only the sky it hides (diffuse rays still see it) is missing.
    ratio = unshadowed[floor_shadow].sum() / empty[floor_shadow].sum()
    assert ratio > 0.9 and shadowed[floor_shadow].sum() / empty[floor_shadow].sum() < 0.5


def test_hidden_from_glossy_rays_leaves_mirrors():
    mirror = Material("mirror", kind="conductor", base_color=(0.9, 0.9, 0.9), roughness=0.0)
    seen, _ = _render(_scene(mirror, ALL_RAYS))
    hidden, _ = _render(_scene(mirror, ALL_RAYS & ~RAY_GLOSSY & ~RAY_CAMERA & ~RAY_SHADOW))
    empty, _ = _render(_scene(mirror, 0, sphere=False))
    assert np.abs(seen - empty).max() > 0.05
    assert np.allclose(hidden, empty)
