"""Film ▸ Exposure (``scene.cycles.film_exposure``, "Image brightness scale": a linear factor, default 1,
range 0 and up) set on a scene made for Cycles scales Prism's image as it scales Cycles': checked on a
flat emissive card against Prism at exposure 1 times the factor (exactly: same seed) and
against Cycles at the same exposure (absolute mean luminance within 2 %). Exposures 0.5 and 2 are one
stop down and up (Cycles' property is a scale, not stops: there is no exposure -1)."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, camera, emission_material, node, plane


def _scene(scene):
    black_world()
    card = emission_material("card", lambda nodes, link: node(nodes, "ShaderNodeRGB").outputs[0])
    card.node_tree.nodes["RGB"].outputs[0].default_value = (0.9, 0.45, 0.2, 1.0)
    plane("Card", 4.0, mat=card)
    camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), resolution=(16, 12))


@pytest.mark.parametrize("exposure", [0.5, 2.0])
def test_film_exposure_scales_the_image_like_cycles(prism_addon, fresh_scene, exposure):
    _scene(fresh_scene)
    base = render_prism_rgba(fresh_scene, samples=4)
    fresh_scene.cycles.film_exposure = exposure
    exposed = render_prism_rgba(fresh_scene, samples=4)
    assert np.allclose(exposed[..., :3], base[..., :3] * exposure, rtol=1e-5, atol=1e-7)
    assert np.allclose(exposed[..., 3], base[..., 3])  # alpha is not light
    cycles = render_cycles_rgba(fresh_scene, samples=4)
    ratio = luminance(exposed).mean() / luminance(cycles).mean()
    print(f"exposure {exposure}: prism / cycles mean luminance {ratio:.4f}")
    assert abs(ratio - 1.0) < 0.02, ratio
