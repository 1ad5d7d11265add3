"""The world "backplate" set-up as Cycles renders it: a Mix Shader whose Fac is Light Path ▸ Is Camera Ray
picks what camera rays see (its second shader) apart from what lights the scene (its first). Rendered by
Cycles and by Prism from the same .blend, compared in absolute light and with the closed forms."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

LIGHTING = (1.0, 1.0, 1.0)  # the Background that lights the card, strength 1
BACKPLATE = (0.8, 0.4, 0.1)  # the Background camera rays see, strength 2
ALBEDO = 0.5


def _backplate_world():
    world = bpy.data.worlds.new("Backplate")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    lighting = nodes["Background"]
    lighting.inputs["Color"].default_value = (*LIGHTING, 1.0)
    seen = nodes.new("ShaderNodeBackground")
    seen.inputs["Color"].default_value = (*BACKPLATE, 1.0)
    seen.inputs["Strength"].default_value = 2.0
    mix = nodes.new("ShaderNodeMixShader")
    path = nodes.new("ShaderNodeLightPath")
    links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    links.new(lighting.outputs[0], mix.inputs[1])
    links.new(seen.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], nodes["World Output"].inputs["Surface"])
    bpy.context.scene.world = world


def _regions(image):
    """(mean RGB of the backplate around the card, mean luminance of the card's centre)."""
    return image[:, :4, :3].reshape(-1, 3).mean(0), float(luminance(image[6:10, 14:18]).mean())


def test_the_backplate_is_seen_and_the_other_background_lights(prism_addon, fresh_scene):
    """A grey card (albedo 0.5) in the open, seen from above: around it the camera sees the backplate
    (2 × orange); the card is lit by the white background alone (radiance ρ · 1 = 0.5)."""
    _backplate_world()
    add_plane("Card", 1.0, color=(ALBEDO,) * 3, specular=0.0)
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    cycles = _regions(render_cycles_rgba(fresh_scene, 64, max_bounces=2))
    prism = _regions(render_prism_rgba(fresh_scene, 64))
    print(f"MEASURED backplate Prism {np.round(prism[0], 4)}, Cycles {np.round(cycles[0], 4)}; card luminance Prism "
          f"{prism[1]:.4f}, Cycles {cycles[1]:.4f}, closed form {ALBEDO}")
    assert np.allclose(prism[0], 2.0 * np.array(BACKPLATE), rtol=0.02)
    assert np.allclose(prism[0], cycles[0], rtol=0.02)
    assert prism[1] == pytest.approx(ALBEDO, rel=0.02)
    assert prism[1] == pytest.approx(cycles[1], rel=0.02)


def test_the_export_keeps_both_backgrounds(prism_addon, fresh_scene):
    _backplate_world()
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export.world")
    warnings = []
    world = export.export_world(fresh_scene, warnings)
    assert world.color == pytest.approx(LIGHTING) and world.strength == 1.0
    assert world.camera_background.color == pytest.approx(BACKPLATE) and world.camera_background.strength == 2.0
    assert warnings == []  # the Light Path link is understood, not reported as ignored


def test_a_link_prism_ignores_in_the_backplate_is_reported_once(prism_addon, fresh_scene):
    """A link into the backplate's Strength that Prism cannot fold is named, as on the lighting side."""
    _backplate_world()
    nodes, links = fresh_scene.world.node_tree.nodes, fresh_scene.world.node_tree.links
    seen = next(n for n in nodes if n.type == "BACKGROUND" and n.name != "Background")
    links.new(nodes.new("ShaderNodeLightPath").outputs["Is Shadow Ray"], seen.inputs["Strength"])
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export.world")
    warnings = []
    world = export.export_world(fresh_scene, warnings)
    named = [w for w in warnings if f"Background '{seen.name}' Strength is ignored" in w]
    assert len(named) == 1, warnings
    assert world.camera_background.strength == 2.0  # the socket's own value
