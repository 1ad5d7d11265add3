"""The scene's light table: which emitters exist, power-proportional selection."""

import numpy as np
import pytest

from engine.tracer.scene import Light, Material, SpectrumSpec

from ..tracer_scenes import plane_under_point_light
from .light_checks import SceneLights


def test_selection_is_proportional_to_power_with_a_floor():
    scene = plane_under_point_light(size=4, power=100.0)
    scene.lights += [Light("area", "area", np.array([0, 0, 3.0]), power_w=300.0, size_u_m=0.5, size_v_m=0.5),
                     Light("dim", "point", np.array([1, 0, 3.0]), power_w=1e-6),
                     Light("off", "point", np.array([1, 0, 3.0]), power_w=0.0)]
    lights = SceneLights(scene)
    a = lights.arrays
    assert lights.table.names == ["lamp", "area", "dim"] and a.mesh_index == -1 and a.environment_index == -1
    p = a.select_prob
    assert p.sum() == pytest.approx(1.0) and p[1] / p[0] == pytest.approx(3.0)
    assert p[2] == pytest.approx(1 / 60, rel=0.05)  # the floor 1/(20 n)
    assert np.all(np.diff(a.select_cdf) >= 0) and a.select_cdf[-1] == 1.0
    # each light is chosen as often as its probability says
    u = np.column_stack([np.full((30000, 2), 0.5), (np.arange(30000) + 0.5) / 30000])
    s = lights.sample(np.zeros((30000, 3)), u)
    chosen_area = ~s.delta
    assert chosen_area.mean() == pytest.approx(p[1], abs=1e-3)


def test_emissive_mesh_is_one_light_and_sun_uses_scene_size():
    scene = plane_under_point_light(size=4, power=10.0)
    scene.materials = [Material("glow", emission=SpectrumSpec(), emission_strength=1.0)]
    scene.lights.append(Light("sun", "sun", np.zeros(3), irradiance_w_m2=1.0))
    a = SceneLights(scene).arrays
    assert a.mesh_index == 2 and len(a.mesh.triangle) == 2
    # floor 40 x 40 m: mesh power pi x 1600, sun E pi R^2 with R = half the diagonal = 20 sqrt 2
    power = np.array([10.0, np.pi * 800, np.pi * 1600])
    prob = np.maximum(power / power.sum(), 1 / 60)  # the point light gets the floor
    assert np.allclose(a.select_prob, prob / prob.sum())
