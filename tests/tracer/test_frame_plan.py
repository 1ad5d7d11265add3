"""Frames of any size: tiles, the memory check, and tiled renders equal to whole ones."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.frame_plan import GB, available_memory_bytes, plan_frame, split_tiles
from engine.tracer.renderer import Renderer

from .tracer_scenes import plane_under_point_light, settings


def test_tiles_cover_the_region_once():
    tiles = split_tiles((3, 2, 50, 41), 16)
    covered = np.zeros((41, 50), int)
    for x0, y0, x1, y1 in tiles:
        assert x1 - x0 <= 16 and y1 - y0 <= 16
        covered[y0:y1, x0:x1] += 1
    assert covered[2:, 3:].min() == 1 and covered.sum() == 47 * 39
    assert split_tiles((0, 0, 16, 16), 16) == [(0, 0, 16, 16)] and split_tiles((0, 0, 99, 99), 0) == [(0, 0, 99, 99)]


def test_a_frame_that_does_not_fit_is_refused_with_the_memory_it_needs(bad_input):
    with pytest.raises(PrismInputError) as error:
        plan_frame(20000, 20000, (0, 0, 20000, 20000), 56, 4, 2048, available_bytes=8 * GB)
    message = str(error.value)
    bad_input("a 20000 x 20000 frame with 8 GB of memory available", 1, message)
    assert message.startswith("a 20000 x 20000 frame needs about 14.8 GB (13.4 GB for the image Blender keeps: "
                              "Combined and 4 more pass channels; 0.4 GB for Prism's tile)")
    assert "only 8.0 GB" in message
    assert "Resolution %" in message
    fits = plan_frame(16384, 16384, (0, 0, 16384, 16384), 56, 4, 2048, available_bytes=24 * GB)
    assert len(fits.tiles) == 64 and fits.prism_bytes < 0.5 * GB and fits.needed_bytes < 15 * GB
    assert available_memory_bytes() is None or available_memory_bytes() > 0


def test_tiles_render_the_same_image_as_the_whole_frame():
    scene = plane_under_point_light(size=20)
    with Renderer(scene, settings(samples=4, samples_per_pass=2)) as whole:
        while not whole.finished:
            whole.render_pass()
        expected = whole.image_rgb()
    with Renderer(scene, settings(samples=4, samples_per_pass=2)) as tiled:
        image = np.zeros_like(expected)
        for x0, y0, x1, y1 in split_tiles(tiled.region, 8):
            tiled.set_region((x0, y0, x1, y1))
            while not tiled.finished:
                tiled.render_pass()
            image[y0:y1, x0:x1] = tiled.film.mean()
            assert tiled.film.mean().shape == (y1 - y0, x1 - x0, 3)
    assert np.array_equal(image, expected)
