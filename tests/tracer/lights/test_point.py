"""Point, spot and sphere lights: inverse-square law, Blender's spot falloff, soft radius."""

import numpy as np
import pytest

from engine.tracer.lights.point import spot_falloff
from engine.tracer.scene import Camera, Light, Material

from ..tracer_scenes import make_scene
from .light_checks import SceneLights


def _lights(*lights):
    return SceneLights(make_scene([], [Material("m")], Camera("c", np.eye(4), (1, 1)), list(lights)))


def test_point_light_intensity_is_power_over_four_pi():
    lights = _lights(Light("p", "point", np.array([0.0, 0.0, 3.0]), power_w=100.0))
    s = lights.sample(np.array([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]]), np.zeros((2, 3)), 500.0)
    assert np.allclose(s.dist, [3.0, 5.0])
    assert np.allclose(s.li / lights.spectrum_at(0, 500.0), 100 / (4 * np.pi) / s.dist**2)
    assert np.allclose(s.wi[1], [-0.8, 0.0, 0.6]) and s.delta.all() and np.all(s.pdf == 1.0)
    assert len(lights.arrays.hittable) == 0


def test_spot_falloff_is_blenders_smoothstep():
    half = np.radians(30.0)
    cos_half = np.cos(half)
    spot = _lights(Light("s", "spot", np.zeros(3), direction=np.array([0.0, 0.0, -1.0]), power_w=10.0,
                         spot_size_rad=2 * half, spot_blend=0.2))
    row = spot.arrays.rows[0]

    def falloff(cos_a):  # at a point 1 m away along a direction with this cosine to the axis
        sin_a = np.sqrt(1 - cos_a * cos_a)
        return spot_falloff(row, sin_a, 0.0, -cos_a)

    assert falloff(1.0) == 1.0 and falloff(cos_half - 1e-6) == 0.0
    assert falloff(cos_half + 0.5 * (1 - cos_half) * 0.2) == pytest.approx(0.5)
    hard = _lights(Light("s", "spot", np.zeros(3), direction=np.array([0.0, 0.0, -1.0]), power_w=10.0,
                         spot_size_rad=2 * half, spot_blend=0.0))
    p = np.array([[0.0, 0.0, -1.0], [1.0, 0.0, -1.0]])  # on the axis, and at 45 degrees (outside)
    s = hard.sample(p, np.zeros((2, 3)), 500.0)
    assert s.li[0] / hard.spectrum_at(0, 500.0) == pytest.approx(10 / (4 * np.pi)) and s.li[1] == 0.0


def test_sphere_light_irradiance_equals_point_light():
    """A uniformly radiant sphere gives exactly I / d^2 on a surface facing it."""
    lights = _lights(Light("p", "point", np.array([0.0, 0.0, 2.0]), power_w=40.0, radius_m=0.5))
    n = 200_000
    p = np.zeros((n, 3))
    s = lights.sample(p, np.random.default_rng(5).random((n, 3)), 500.0)
    est = s.li / lights.spectrum_at(0, 500.0) * s.wi[:, 2] / s.pdf
    assert est.mean() == pytest.approx(40 / (4 * np.pi) / 4.0, rel=0.005)
    index, t, factor, pdf = lights.hit(p, s.wi)
    assert np.all(index == 0) and np.allclose(t, s.dist) and np.allclose(pdf, s.pdf)
    assert not s.delta.any() and lights.arrays.hittable.tolist() == [0]
