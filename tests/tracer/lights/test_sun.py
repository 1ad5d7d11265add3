"""Sun: irradiance on a facing surface equals its strength, delta or with an angle."""

import numpy as np
import pytest

from engine.tracer.lights.sun import SunLight
from engine.tracer.scene import Light


def ones(lam):
    return np.ones(np.shape(lam))


@pytest.mark.parametrize("angle_deg", [0.0, 0.53, 10.0])
def test_irradiance_on_facing_surface_is_strength(angle_deg):
    d = np.array([0.3, -0.2, -1.0])
    sun = SunLight(Light("sun", "sun", np.zeros(3), direction=d, irradiance_w_m2=3.0,
                         sun_angle_rad=np.radians(angle_deg)), ones)
    normal = -d / np.linalg.norm(d)
    n = 100_000
    rng = np.random.default_rng(6)
    wi, dist, li, pdf = sun.sample(np.zeros((n, 3)), rng.random((n, 3)), np.full((n, 1), 500.0))
    assert np.all(np.isinf(dist))
    assert (li[:, 0] * (wi @ normal) / pdf).mean() == pytest.approx(3.0, rel=1e-3)
    if angle_deg > 0:
        assert np.allclose(sun.pdf_escaped(wi), pdf) and np.allclose(sun.escaped(wi, np.ones((n, 1)))[:, 0], li[:, 0])
        assert sun.escaped(-wi[:1], np.ones((1, 1)))[0, 0] == 0.0
