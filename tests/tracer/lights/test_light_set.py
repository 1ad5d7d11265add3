"""The scene's light set: which emitters exist, power-proportional selection."""

import numpy as np
import pytest

from engine.tracer import path_spectra as spectra
from engine.tracer.lights import LightSet
from engine.tracer.scene import Light, Material, SpectrumSpec

from ..tracer_scenes import plane_under_point_light


def test_selection_is_proportional_to_power_with_a_floor():
    scene = plane_under_point_light(size=4, power=100.0)
    scene.lights += [Light("area", "area", np.array([0, 0, 3.0]), power_w=300.0, size_u_m=0.5, size_v_m=0.5),
                     Light("dim", "point", np.array([1, 0, 3.0]), power_w=1e-6),
                     Light("off", "point", np.array([1, 0, 3.0]), power_w=0.0)]
    ls = LightSet(scene, spectra)
    assert len(ls) == 3 and ls.mesh is None and ls.world.black
    p = ls.select_prob
    assert p.sum() == pytest.approx(1.0) and p[1] / p[0] == pytest.approx(3.0)
    assert p[2] == pytest.approx(1 / 60, rel=0.05)  # the floor 1/(20 n)
    assert np.all(np.diff(ls.select_cdf) >= 0) and ls.select_cdf[-1] == pytest.approx(1.0)


def test_emissive_mesh_is_one_light_and_sun_uses_scene_size():
    scene = plane_under_point_light(size=4, power=10.0)
    scene.materials = [Material("glow", emission=SpectrumSpec(), emission_strength=1.0)]
    scene.lights.append(Light("sun", "sun", np.zeros(3), irradiance_w_m2=1.0))
    ls = LightSet(scene, spectra)
    assert ls.mesh is not None and ls.mesh_index == 2
    # floor 40 x 40 m: mesh power pi x 1600, sun E pi R^2 with R = half the diagonal = 20 sqrt 2
    power = np.array([10.0, np.pi * 800, np.pi * 1600])
    prob = np.maximum(power / power.sum(), 1 / 60)  # the point light gets the floor
    assert np.allclose(ls.select_prob, prob / prob.sum())
    assert len(LightSet(scene, spectra, use_mesh_lights=False)) == 2
