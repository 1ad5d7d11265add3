"""Geometry relative to the camera: a scene 1e7 m from the origin renders like the same scene at it."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _tabletop(offset):
    """A 2 cm marble on a 10 cm card lit by a point light, seen from 15 cm: millimetre-scale detail."""
    offset = np.asarray(offset, np.float64)
    card = quad(offset, (0.05, 0, 0), (0, 0.05, 0))
    marble = uv_sphere(offset + [0.0, 0.0, 0.01], 0.01, rings=16, segments=32)
    cam = Camera("cam", look_at(offset + [0.0, -0.1, 0.1], offset + [0, 0, 0.005]), (24, 24),
                 film_width_mm=24.0, film_height_mm=24.0)
    mats = [Material("card", base_color=(0.7, 0.7, 0.7)), Material("marble", base_color=(0.8, 0.2, 0.1))]
    light = Light("lamp", "point", offset + [0.03, -0.03, 0.08], power_w=0.05)
    return make_scene([(*card, 0), (*marble, 1)], mats, cam, [light])


def test_far_from_the_origin_renders_like_at_the_origin():
    near = Renderer(_tabletop((0.0, 0.0, 0.0)), settings(samples=16, samples_per_pass=16, seed=3))
    far = Renderer(_tabletop((1e7, -2e7, 3e6)), settings(samples=16, samples_per_pass=16, seed=3))
    near.render_pass()
    far.render_pass()
    a, b = near.image_rgb().astype(np.float64), far.image_rgb().astype(np.float64)
    marble = a[..., 0] > 1.5 * a[..., 1]  # the red marble's pixels
    assert marble.sum() > 20  # the marble is there...
    assert (b[..., 0] > 1.5 * b[..., 1]).sum() == pytest.approx(marble.sum(), abs=3)  # ...and stays there
    assert np.abs(a - b).mean() < 1e-4 * a.mean()
