"""View Layer ▸ Filter ▸ Environment off, as Cycles: the world is neither seen nor lights the scene
(Cycles swaps in an empty background shader); the film shows black where the world was."""

from __future__ import annotations

import bpy
import pytest

from helpers.batch import run_batch
from helpers.bpy_scenes import add_camera, add_plane, add_point_light
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

WORLD = 1.0  # the world's radiance (white)


def _regions(image):
    """(mean luminance of the world around the card, of the card)."""
    lum = luminance(image)
    return float(lum[:, list(range(0, 7)) + list(range(26, 32))].mean()), float(lum[3:13, 11:21].mean())


@pytest.mark.parametrize("environment", [True, False])
def test_environment_filter_as_in_cycles(prism_addon, fresh_scene, environment):
    """A grey card under a point light and a white world, seen from above. Environment on: the world
    (luminance 1) shows around the card and lights it; off: black around it, the card lit by the bulb
    alone, as bright as Cycles renders it (within 4 %)."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = WORLD
    fresh_scene.world = world
    add_plane("Card", 1.2, color=(0.5, 0.5, 0.5), specular=0.0)
    add_point_light("Bulb", 50.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    bpy.context.view_layer.use_sky = environment
    cycles = _regions(render_cycles_rgba(fresh_scene, 64, max_bounces=2))
    prism = _regions(render_prism_rgba(fresh_scene, 64))
    assert cycles[0] == pytest.approx(WORLD if environment else 0.0, abs=1e-3)
    assert prism[0] == pytest.approx(WORLD if environment else 0.0, abs=1e-3)
    assert prism[1] == pytest.approx(cycles[1], rel=0.04), (prism, cycles)


def test_a_scene_lit_by_its_world_alone_with_environment_off_names_the_filter(prism_addon, fresh_scene, tmp_path,
                                                                             capsys, bad_input):
    """Cycles renders it black; Prism refuses, naming the view layer's filter (not "a black world")."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    fresh_scene.world = world
    add_plane("Card", 1.2)
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    bpy.context.view_layer.use_sky = False
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status == 1
    assert line == ("Prism: error: Scene 'Scene' has no light (no light with power, no emissive material, and View "
                    "Layer 'ViewLayer' ▸ Filter ▸ Environment is off, so the world lights nothing, as in Cycles): "
                    "turn Environment on or add a light, or the image would be black.")
    bad_input("a scene lit by its world alone, with View Layer ▸ Filter ▸ Environment off", status, line)
