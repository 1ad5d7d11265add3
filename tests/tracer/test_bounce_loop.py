"""The compiled bounce loops (``stages.bounce_loop``, ``stages.light_loop``) make the image the
stepwise loop makes (stage kernels called from Python, Embree queried on whole queues in between), bit
for bit: Combined and every pass, light-traced splats, shadow rays through films, any thread count."""

import numpy as np
import pytest

from engine.tracer.pass_table import PASSES, PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import World

from .test_light_tracing import _ball_on_floor
from .tracer_scenes import settings


def _images(scene, compiled, **kw):
    with Renderer(scene, settings(**kw)) as r:
        r.tables.accel.compiled_loops = compiled
        while not r.finished:
            r.render_pass()
        film = r.film
        light = None if film.light_paths == 0 else film._light_sum.copy()
        return r.image_rgb().copy(), r.pass_images(), light, dict(r.stats)


def _assert_same(scene, **kw):
    a_image, a_passes, a_light, a_stats = _images(scene, True, **kw)
    b_image, b_passes, b_light, b_stats = _images(scene, False, **kw)
    assert a_image.any()
    np.testing.assert_array_equal(a_image, b_image)
    assert a_passes.keys() == b_passes.keys()
    for name in a_passes:
        np.testing.assert_array_equal(a_passes[name], b_passes[name], err_msg=name)
    if a_light is None or b_light is None:
        assert a_light is None and b_light is None
    else:
        np.testing.assert_array_equal(a_light, b_light)
    assert a_stats["rays_cast"] == b_stats["rays_cast"]
    return a_stats


@pytest.mark.parametrize("threads", [1, 2])
def test_cornell_glass_with_every_pass_is_the_stepwise_image(threads):
    from benchmarks import scenes

    scene = scenes.cornell_glass((20, 20))
    scene.world = World((0.3, 0.4, 0.5), 1.0)
    _assert_same(scene, samples=4, samples_per_pass=4, threads=threads, passes=PassRequest(tuple(PASSES)))


def test_light_traced_caustics_are_the_stepwise_splats():
    stats = _assert_same(_ball_on_floor(resolution=(24, 18)), samples=4, samples_per_pass=4, light_tracing="on")
    assert stats["light_splats"] > 0


def test_shadow_rays_through_films_are_the_stepwise_ones():
    from benchmarks import scenes

    _assert_same(scenes.soap_bubble((20, 20)), samples=4, samples_per_pass=4)


def test_clip_end_in_the_compiled_loop_is_the_stepwise_one():
    from dataclasses import replace

    from benchmarks import scenes

    scene = scenes.cornell_glass((20, 20))
    scene.world = World((0.3, 0.4, 0.5), 1.0)
    unclipped = _images(scene, True, samples=2, samples_per_pass=2)[0]
    scene.camera = replace(scene.camera, clip_end_m=4.5)  # the back wall (4.8 m deep) is beyond it
    clipped = _images(scene, True, samples=2, samples_per_pass=2)[0]
    centre = (slice(8, 12), slice(8, 12))
    assert not np.allclose(clipped[centre], unclipped[centre])  # the world shows where the wall was
    _assert_same(scene, samples=2, samples_per_pass=2)
