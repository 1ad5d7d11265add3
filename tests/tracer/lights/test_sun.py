"""Sun: irradiance on a facing surface equals its strength, delta or with an angle; the disc is seen by
escaping rays with the density it is sampled with."""

import numpy as np
import pytest

from engine.tracer.lights.dispatch import distant_hit, is_distant
from engine.tracer.scene import Camera, Light, Material

from ..tracer_scenes import make_scene
from .light_checks import SceneLights


@pytest.mark.parametrize("angle_deg", [0.0, 0.53, 10.0])
def test_irradiance_on_facing_surface_is_strength(angle_deg):
    d = np.array([0.3, -0.2, -1.0])
    sun = Light("sun", "sun", np.zeros(3), direction=d, irradiance_w_m2=3.0, sun_angle_rad=np.radians(angle_deg))
    lights = SceneLights(make_scene([], [Material("m")], Camera("c", np.eye(4), (1, 1)), [sun]))
    normal = -d / np.linalg.norm(d)
    n = 100_000
    s = lights.sample(np.zeros((n, 3)), np.random.default_rng(6).random((n, 3)), 500.0)
    assert np.all(np.isinf(s.dist))
    scale = lights.spectrum_at(0, 500.0)
    assert (s.li / scale * (s.wi @ normal) / s.pdf).mean() == pytest.approx(3.0, rel=1e-3)
    assert is_distant(lights.arrays, 0) == (angle_deg > 0)
    if angle_deg > 0:
        seen = np.array([distant_hit(lights.arrays, 0, tuple(w)) for w in s.wi[:1000]])
        assert np.allclose(seen[:, 1], s.pdf[:1000]) and np.allclose(seen[:, 0] * scale, s.li[:1000])
        assert distant_hit(lights.arrays, 0, tuple(-s.wi[0]))[0] == 0.0
