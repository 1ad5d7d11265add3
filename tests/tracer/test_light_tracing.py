"""Light tracing for caustics: the split with path tracing adds up (a furnace, a long path-traced
render), caustic lines land where Snell's law puts them, and renders stay deterministic."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec
from engine.tracer.spectra.rgb_to_spectrum import white_rgb

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _blocks(image, size):
    h, w = image.shape[:2]
    return image[:h - h % size, :w - w % size].reshape(h // size, size, w // size, size, -1).mean((1, 3))


def _light_part(renderer):
    """The light-traced share of the image, float64 [H, W, 3]."""
    film = renderer.film
    return (film._light_sum / film.light_paths).reshape(film.height, film.width, 3)


def _render(scene, **kw):
    r = Renderer(scene, settings(**kw))
    while r.samples_done < r.settings.samples:
        r.render_pass()
    return r


def test_furnace_with_a_mirror_ball_stays_uniform():
    """A closed sphere that emits E and reflects a (Lambert) is filled with radiance E / (1 - a)
    everywhere; a mirror ball inside changes nothing. The wall around the ball receives a few per
    cent of it as caustics (light → mirror → wall): with light tracing supplying them and path
    tracing skipping them, every part of the image still sees E / (1 - a)."""
    a = 0.5
    shell = uv_sphere((0, 0, 0), 1.0, rings=24, segments=48, inward=True)
    ball = uv_sphere((0.0, 0.35, -0.1), 0.4, rings=24, segments=48)
    materials = [Material("glow", base_color=(a,) * 3, emission=SpectrumSpec(), emission_strength=1.0),
                 Material("mirror", kind="conductor", base_color=(1.0, 1.0, 1.0))]
    camera = Camera("cam", look_at((0, -0.9, 0.0), (0, 1, -0.3)), (32, 32), film_width_mm=36.0, film_height_mm=36.0)
    r = _render(make_scene([(*shell, 0), (*ball, 1)], materials, camera), samples=128, samples_per_pass=64,
                max_bounces=32, light_tracing="on")
    assert "caustics by light tracing (mirror)" in r.strategy and r.stats["nan_samples"] == 0
    white = np.asarray(white_rgb()) / (1 - a)
    image = _blocks(r.image_rgb().astype(np.float64) / white, 4).mean(-1)
    stderr = np.sqrt(_blocks(r.variance_rgb().astype(np.float64) / white ** 2, 4).mean(-1) / 16)
    caustics = _blocks(_light_part(r) / white, 4).mean(-1)
    assert caustics.max() > 0.04  # what the light tracer contributes is far above the tolerance below
    assert np.all(np.abs(image - 1.0) < 4 * stderr + 1e-3), (image - 1.0) / stderr
    assert image.mean() == pytest.approx(1.0, abs=0.004)


def _ball_on_floor(resolution=(32, 24), **camera):
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    ball = uv_sphere((0, 0, 0.5), 0.5, rings=32, segments=64)
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)), Material("glass", kind="dielectric", glass="N-BK7")]
    light = Light("key", "area", np.array([0.6, 0.0, 2.5]), direction=np.array([-0.2, 0, -1.0]), power_w=300.0,
                  size_u_m=0.8, size_v_m=0.8)
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), resolution, film_width_mm=36, film_height_mm=27,
                 **camera)
    return make_scene([(*floor, 0), (*ball, 1)], materials, cam, [light])


@pytest.mark.parametrize("camera, filter", [({}, "box"),
                                            (dict(model="thin_lens", fstop=0.5, focus_distance_m=3.0), "gaussian")])
def test_caustic_of_a_glass_ball_agrees_with_long_path_tracing(camera, filter):
    """A big area light over a glass ball: path tracing alone converges here, slowly. The split
    (caustics by light tracing, the rest by path tracing) agrees with it block by block, in the
    caustic too, through a pinhole with the box filter and a thin lens with the Gaussian filter."""
    scene = _ball_on_floor(**camera)
    reference = _render(scene, samples=1024, samples_per_pass=256, max_bounces=6, light_tracing="off", seed=7,
                        pixel_filter=filter)
    split = _render(scene, samples=256, samples_per_pass=128, max_bounces=6, light_tracing="on", seed=8,
                    pixel_filter=filter)
    assert reference.stats["light_splats"] == 0 and split.stats["light_splats"] > 10_000
    a, b = (_blocks(r.image_rgb().astype(np.float64), 4).mean(-1) for r in (reference, split))
    var = sum(_blocks(r.variance_rgb().astype(np.float64), 4).mean(-1) / 16 for r in (reference, split))
    z = (a - b) / np.sqrt(var + 1e-12)
    caustic = _blocks(_light_part(split), 4).mean(-1) > 0.25 * b
    assert caustic.sum() >= 2  # blocks where light tracing brings a quarter of the light or more
    assert np.all(np.abs(z) < 4.5), z
    assert np.abs(z[caustic]).max() < 3.5 and abs(z.mean()) < 0.5, (z.mean(), z[caustic])
    print("caustic sums", a[caustic].sum(), b[caustic].sum(), np.sqrt(var[caustic].sum()), z[caustic])
    assert abs(b[caustic].sum() - a[caustic].sum()) < 3.5 * np.sqrt(var[caustic].sum())


def test_chunks_threads_and_sample_chunks_give_identical_light_traced_images():
    scene = _ball_on_floor(resolution=(64, 64))
    images = []
    for threads in (1, 2):  # 64 x 64 x 4 paths: 2 chunks with one thread, 4 with two
        with Renderer(scene, settings(samples=4, samples_per_pass=4, threads=threads, light_tracing="on")) as r:
            r.render_pass()
            assert r.stats["light_splats"] > 0
            images.append(r.film.mean())
    assert np.array_equal(images[0], images[1])
    with Renderer(scene, settings(samples=4, samples_per_pass=2, light_tracing="on")) as whole, \
            Renderer(scene, settings(samples=2, samples_per_pass=2, light_tracing="on")) as first, \
            Renderer(scene, settings(samples=2, samples_per_pass=2, light_tracing="on")) as second:
        whole.render_pass()
        whole.render_pass()
        first.render_pass()
        second.start_at_sample(2)
        second.render_pass()
        assert first.film.light_paths + second.film.light_paths == whole.film.light_paths
        assert np.array_equal(first.film._light_sum + second.film._light_sum, whole.film._light_sum)


def test_scenes_without_caustics_render_exactly_as_with_light_tracing_off():
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    rough = uv_sphere((0, 0, 0.5), 0.5, rings=8, segments=16)
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)),
                 Material("frosted", kind="dielectric", glass="N-BK7", roughness=0.4)]
    light = Light("lamp", "point", np.array([0.5, 0.0, 2.0]), power_w=100.0)
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), (16, 12), film_width_mm=36, film_height_mm=27)
    scene = make_scene([(*floor, 0), (*rough, 1)], materials, cam, [light])
    images = {}
    for mode in ("auto", "off"):
        with Renderer(scene, settings(samples=4, light_tracing=mode)) as r:
            r.render_pass()
            assert not r.analysis.light_tracing and r.film.light_paths == 0
            images[mode] = r.film.mean()
    with Renderer(scene, settings()) as r:
        assert "no caustics to light-trace" in r.strategy
    assert np.array_equal(images["auto"], images["off"])
