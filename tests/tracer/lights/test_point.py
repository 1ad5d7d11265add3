"""Point, spot and sphere lights: inverse-square law, Blender's spot falloff, soft radius."""

import numpy as np
import pytest

from engine.tracer.lights.point import PointLight, spot_falloff
from engine.tracer.scene import Light


def ones(lam):
    return np.ones(np.shape(lam))


def test_point_light_intensity_is_power_over_four_pi():
    light = PointLight(Light("p", "point", np.array([0.0, 0.0, 3.0]), power_w=100.0), ones)
    p = np.array([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]])
    wi, dist, li, pdf = light.sample(p, np.zeros((2, 3)), np.full((2, 1), 500.0))
    assert np.allclose(dist, [3.0, 5.0])
    assert np.allclose(li[:, 0], 100 / (4 * np.pi) / dist**2)
    assert np.allclose(wi[1], [-0.8, 0.0, 0.6]) and light.delta


def test_spot_falloff_is_blenders_smoothstep():
    half = np.radians(30.0)
    cos_half = np.cos(half)
    assert spot_falloff(np.array([1.0, cos_half - 1e-6]), cos_half, 0.2).tolist() == [1.0, 0.0]
    mid = cos_half + 0.5 * (1 - cos_half) * 0.2
    assert spot_falloff(np.array([mid]), cos_half, 0.2)[0] == pytest.approx(0.5)
    assert spot_falloff(np.array([cos_half + 1e-9]), cos_half, 0.0)[0] == 1.0
    spot = PointLight(Light("s", "spot", np.zeros(3), direction=np.array([0.0, 0.0, -1.0]), power_w=10.0,
                            spot_size_rad=2 * half, spot_blend=0.0), ones, spot=True)
    p = np.array([[0.0, 0.0, -1.0], [1.0, 0.0, -1.0]])  # on the axis, and at 45 degrees (outside)
    _, _, li, _ = spot.sample(p, np.zeros((2, 3)), np.full((2, 1), 500.0))
    assert li[0, 0] == pytest.approx(10 / (4 * np.pi)) and li[1, 0] == 0.0


def test_sphere_light_irradiance_equals_point_light():
    """A uniformly radiant sphere gives exactly I / d^2 on a surface facing it."""
    light = PointLight(Light("p", "point", np.array([0.0, 0.0, 2.0]), power_w=40.0, radius_m=0.5), ones)
    n = 200_000
    rng = np.random.default_rng(5)
    p = np.zeros((n, 3))
    wi, dist, li, pdf = light.sample(p, rng.random((n, 3)), np.full((n, 1), 500.0))
    est = li[:, 0] * wi[:, 2] / pdf
    assert est.mean() == pytest.approx(40 / (4 * np.pi) / 4.0, rel=0.005)
    t = light.intersect(p, wi)
    assert np.allclose(t, dist) and np.allclose(light.pdf(p, wi, t), pdf)
    assert not light.delta and light.hittable
