"""Area lights: sampled irradiance against quadrature, pdf/intersection consistency, one-sidedness."""

import numpy as np
import pytest

from engine.tracer.lights.row import L_AREA, L_HALF_U, L_HALF_V, L_NX, L_PX, L_UX, L_VX, DISK, L_KIND
from engine.tracer.scene import Camera, Light, Material

from ..tracer_scenes import make_scene
from .light_checks import SceneLights


def _lights(shape, size_u=1.0, size_v=0.6, power=50.0):
    light = Light("a", "area", np.array([0.2, -0.1, 2.0]), direction=np.array([0.0, 0.3, -1.0]) / np.sqrt(1.09),
                  axis_u=np.array([1.0, 0.0, 0.0]), axis_v=np.array([0.0, 1.0, 0.3]) / np.sqrt(1.09),
                  power_w=power, area_shape=shape, size_u_m=size_u, size_v_m=size_v)
    return SceneLights(make_scene([], [Material("m")], Camera("c", np.eye(4), (1, 1)), [light]))


def _quadrature_irradiance(row, p, normal, m=400):
    g = (np.arange(m) + 0.5) / m * 2 - 1
    x, y = np.meshgrid(g, g)
    x, y = x.ravel(), y.ravel()
    inside = (x * x + y * y <= 1) if row[L_KIND] == DISK else np.ones_like(x, bool)
    centre, n, u, v = (row[c:c + 3] for c in (L_PX, L_NX, L_UX, L_VX))
    q = centre + (x * row[L_HALF_U])[:, None] * u + (y * row[L_HALF_V])[:, None] * v
    w = q - p
    d2 = (w * w).sum(1)
    w /= np.sqrt(d2)[:, None]
    cos_r = np.clip(w @ normal, 0, None)
    cos_l = np.clip(-(w @ n), 0, None)
    da = 4 * row[L_HALF_U] * row[L_HALF_V] / (m * m)
    radiance = 50.0 / (np.pi * row[L_AREA])
    return float((radiance * cos_r * cos_l / d2 * inside).sum() * da)


@pytest.mark.parametrize("shape", ["rectangle", "disk"])
def test_sampled_irradiance_matches_quadrature(shape):
    lights = _lights(shape)
    row = lights.arrays.rows[0]
    p = np.array([0.5, 0.3, 0.0])
    normal = np.array([0.0, 0.0, 1.0])
    n = 200_000
    s = lights.sample(np.repeat(p[None], n, 0), np.random.default_rng(3).random((n, 3)))
    est = s.li / lights.spectrum_at(0) * np.clip(s.wi @ normal, 0, None) / s.pdf
    assert est.mean() == pytest.approx(_quadrature_irradiance(row, p, normal), rel=0.01)
    area = (np.pi if shape == "disk" else 4.0) * 0.5 * 0.3
    assert row[L_AREA] == pytest.approx(area) and not s.delta.any()


@pytest.mark.parametrize("shape", ["rectangle", "disk"])
def test_intersection_and_pdf_agree_with_sampling(shape):
    lights = _lights(shape)
    n = 1000
    rng = np.random.default_rng(4)
    p = np.column_stack([rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), np.zeros(n)])
    s = lights.sample(p, rng.random((n, 3)))
    index, t, factor, pdf = lights.hit(p, s.wi)
    assert np.all(index == 0)
    assert np.allclose(t, s.dist, rtol=1e-9) and np.allclose(pdf, s.pdf, rtol=1e-9)
    assert np.allclose(factor * lights.spectrum_at(0), s.li)
    # the back face is invisible, and a hit beyond t_max does not count
    assert np.all(lights.hit(p + 2 * s.dist[:, None] * s.wi, -s.wi)[0] == -1)
    assert np.all(lights.hit(p, s.wi, 0.5 * s.dist)[0] == -1)
