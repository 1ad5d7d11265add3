"""Area lights: sampled irradiance against quadrature, pdf/intersection consistency."""

import numpy as np
import pytest

from engine.tracer.lights.area import AreaLight
from engine.tracer.scene import Light


def ones(lam):
    return np.ones(np.shape(lam))


def _light(shape, size_u=1.0, size_v=0.6, power=50.0):
    return Light("a", "area", np.array([0.2, -0.1, 2.0]), direction=np.array([0.0, 0.3, -1.0]) / np.sqrt(1.09),
                 axis_u=np.array([1.0, 0.0, 0.0]), axis_v=np.array([0.0, 1.0, 0.3]) / np.sqrt(1.09),
                 power_w=power, area_shape=shape, size_u_m=size_u, size_v_m=size_v)


def _quadrature_irradiance(light, p, normal, m=400):
    g = (np.arange(m) + 0.5) / m * 2 - 1
    x, y = np.meshgrid(g, g)
    x, y = x.ravel(), y.ravel()
    inside = (x * x + y * y <= 1) if light.disk else np.ones_like(x, bool)
    q = light.center + (x * light.half_u)[:, None] * light.axis_u + (y * light.half_v)[:, None] * light.axis_v
    w = q - p
    d2 = (w * w).sum(1)
    w /= np.sqrt(d2)[:, None]
    cos_r = np.clip(w @ normal, 0, None)
    cos_l = np.clip(-(w @ light.normal), 0, None)
    da = 4 * light.half_u * light.half_v / (m * m)
    return float((light.radiance * cos_r * cos_l / d2 * inside).sum() * da)


@pytest.mark.parametrize("shape", ["rectangle", "disk"])
def test_sampled_irradiance_matches_quadrature(shape):
    light = AreaLight(_light(shape), ones)
    p = np.array([[0.5, 0.3, 0.0]])
    normal = np.array([0.0, 0.0, 1.0])
    n = 200_000
    rng = np.random.default_rng(3)
    wi, dist, li, pdf = light.sample(np.repeat(p, n, 0), rng.random((n, 3)), np.full((n, 1), 550.0))
    est = li[:, 0] * np.clip(wi @ normal, 0, None) / pdf
    assert est.mean() == pytest.approx(_quadrature_irradiance(light, p[0], normal), rel=0.01)
    assert light.radiance == pytest.approx(50.0 / (np.pi * light.area))


@pytest.mark.parametrize("shape", ["rectangle", "disk"])
def test_intersection_and_pdf_agree_with_sampling(shape):
    light = AreaLight(_light(shape), ones)
    n = 1000
    rng = np.random.default_rng(4)
    p = np.column_stack([rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), np.zeros(n)])
    wi, dist, li, pdf = light.sample(p, rng.random((n, 3)), np.full((n, 1), 550.0))
    t = light.intersect(p, wi)
    assert np.allclose(t, dist, rtol=1e-9)
    assert np.allclose(light.pdf(p, wi, t), pdf, rtol=1e-9)
    # the back face is invisible
    assert np.all(np.isinf(light.intersect(p + 2 * dist[:, None] * wi, -wi)))
