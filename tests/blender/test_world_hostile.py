"""Hostile worlds: Backgrounds summed by Add Shader and Mix Shader render as Cycles sums them, a constant
Value node driving a Background's Strength is folded, a link Prism cannot evaluate is reported (also when
it is why the scene has no light), and a Sky Texture with a NaN setting is refused naming world and setting.
"""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane
from helpers.batch_outcome import batch_refusal, batch_warning
from helpers.bpy_worlds import blender_image, environment_world, sky_world
from helpers.error_scenes import base_scene

ORANGE = (1.0, 0.4, 0.05)


def _export(addon):
    warnings = []
    export = importlib.import_module(f"{addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings), warnings


def _export_error(addon) -> str:
    errors = importlib.import_module(f"{addon.__name__}.engine.tracer.errors")
    with pytest.raises(errors.PrismInputError) as caught:
        _export(addon)
    return str(caught.value)


def summed_world(name="Sum", shader="ShaderNodeAddShader", colours=((0.0, 0.0, 0.0), ORANGE), strengths=(1.0, 2.0),
                 fac=0.5):
    """World Output ▸ Surface ← Add (or Mix) Shader of two Backgrounds of ``colours`` and ``strengths``."""
    world = bpy.data.worlds.new(name)
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    first = nodes["Background"]
    second = nodes.new("ShaderNodeBackground")
    combine = nodes.new(shader)
    offset = 0 if shader == "ShaderNodeAddShader" else 1
    if shader == "ShaderNodeMixShader":
        combine.inputs["Fac"].default_value = fac
    for node, colour, strength, slot in zip((first, second), colours, strengths, (0, 1)):
        node.inputs["Color"].default_value = (*colour, 1.0)
        node.inputs["Strength"].default_value = strength
        links.new(node.outputs[0], combine.inputs[slot + offset])
    links.new(combine.outputs[0], nodes["World Output"].inputs["Surface"])
    bpy.context.scene.world = world
    return world


def _radiance(world):
    return np.array(world.color) * world.strength


def test_add_shader_of_a_black_and_an_orange_background_is_their_sum(prism_addon, fresh_scene):
    base_scene()
    bpy.data.objects.remove(bpy.data.objects["Bulb"])  # the world alone lights the scene: not refused as black
    summed_world()
    scene, _ = _export(prism_addon)
    assert scene.world.kind == "constant"
    assert np.allclose(_radiance(scene.world), 2.0 * np.array(ORANGE), rtol=1e-6)


def test_mix_shader_of_two_backgrounds_is_their_weighted_sum(prism_addon, fresh_scene):
    base_scene()
    summed_world(shader="ShaderNodeMixShader", colours=((0.2, 0.2, 0.2), ORANGE), strengths=(1.0, 3.0), fac=0.25)
    scene, _ = _export(prism_addon)
    assert np.allclose(_radiance(scene.world), 0.75 * 0.2 + 0.25 * 3.0 * np.array(ORANGE), rtol=1e-6)


def test_a_constant_background_added_to_an_hdri_is_added_to_its_texels(prism_addon, fresh_scene):
    base_scene()
    texels = np.full((4, 8, 3), 0.5, np.float32)
    world = environment_world(blender_image("grey", texels), strength=2.0)
    nodes, links = world.node_tree.nodes, world.node_tree.links
    extra, add = nodes.new("ShaderNodeBackground"), nodes.new("ShaderNodeAddShader")
    extra.inputs["Color"].default_value = (*ORANGE, 1.0)
    links.new(nodes["Background"].outputs[0], add.inputs[0])
    links.new(extra.outputs[0], add.inputs[1])
    links.new(add.outputs[0], nodes["World Output"].inputs["Surface"])
    scene, _ = _export(prism_addon)
    assert scene.world.kind == "image"
    seen = scene.world.strength * scene.world.image_rgb
    assert np.allclose(seen, 2.0 * 0.5 + np.array(ORANGE), rtol=1e-5)


def test_a_sky_summed_with_another_background_is_refused(prism_addon, fresh_scene, bad_input, capsys, tmp_path):
    base_scene()
    world = sky_world()
    nodes, links = world.node_tree.nodes, world.node_tree.links
    extra, add = nodes.new("ShaderNodeBackground"), nodes.new("ShaderNodeAddShader")
    links.new(nodes["Background"].outputs[0], add.inputs[0])
    links.new(extra.outputs[0], add.inputs[1])
    links.new(add.outputs[0], nodes["World Output"].inputs["Surface"])
    message = _export_error(prism_addon)
    assert message.startswith("World 'Sky': a Sky Texture is summed with another Background")
    bad_input("world: Add Shader of a Sky Texture's Background and a grey Background",
              *batch_refusal(capsys, tmp_path, message))


@pytest.mark.parametrize("setting, label", [("sun_elevation", "Sun Elevation"), ("air_density", "Air")])
def test_a_sky_with_a_nan_setting_is_refused(prism_addon, fresh_scene, bad_input, capsys, tmp_path, setting, label):
    base_scene()
    sky_world(**{setting: math.nan})
    message = _export_error(prism_addon)
    assert message == (f"World 'Sky', Sky Texture 'Sky Texture': {label} is nan; enter a finite number "
                       f"(Sky Texture ▸ {label}).")
    bad_input(f"Nishita sky with {label} NaN", *batch_refusal(capsys, tmp_path, message))


def _strength_from(kind, own_strength):
    world = bpy.data.worlds.new("Driven")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Color"].default_value = (*ORANGE, 1.0)
    background.inputs["Strength"].default_value = own_strength
    source = nodes.new(kind)
    if kind == "ShaderNodeValue":
        source.outputs[0].default_value = 3.0
    links.new(source.outputs[0], background.inputs["Strength"])
    bpy.context.scene.world = world
    return source


def test_a_value_node_driving_the_strength_is_folded(prism_addon, fresh_scene):
    base_scene()
    bpy.data.objects.remove(bpy.data.objects["Bulb"])  # lit by the world alone: it was refused as "a black world"
    _strength_from("ShaderNodeValue", own_strength=0.0)
    scene, warnings = _export(prism_addon)
    assert scene.world.strength == pytest.approx(3.0)
    assert not [w for w in warnings if w.startswith("World")]


def test_a_link_prism_cannot_evaluate_is_reported_where_it_is_ignored(prism_addon, fresh_scene, bad_input, capsys,
                                                                      tmp_path):
    base_scene()
    _strength_from("ShaderNodeLightPath", own_strength=0.5)
    scene, warnings = _export(prism_addon)
    expected = ("World 'Driven': the link from 'Light Path' into Background 'Background' Strength is ignored; Prism "
                "folds only Value and RGB nodes there and uses the socket's own value 0.5.")
    assert expected in warnings
    assert scene.world.strength == pytest.approx(0.5)
    bad_input("world Background Strength driven by a Light Path node", *batch_warning(capsys, tmp_path, expected))
    # without other light, the refusal tells why the world is black (a refused render prints no warnings)
    bpy.data.objects.remove(bpy.data.objects["Bulb"])
    bpy.data.worlds["Driven"].node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    message = _export_error(prism_addon)
    assert message.startswith("Scene 'Scene' has no light")
    assert "the link from 'Light Path' into Background 'Background' Strength is ignored" in message
    bad_input("world lit only through a Light Path node into Strength (own value 0), no light",
              *batch_refusal(capsys, tmp_path, message))


def test_added_backgrounds_render_as_in_cycles(prism_addon, fresh_scene):
    """The camera sees the Add Shader world directly (and a speck of geometry Prism needs): the same
    orange as Cycles, where Prism rendered black before."""
    from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

    summed_world()
    add_plane("Speck", 0.001, location=(0.0, 0.0, -50.0))
    add_camera((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), resolution=(4, 4))
    cycles = luminance(render_cycles_rgba(fresh_scene, 1))
    prism = luminance(render_prism_rgba(fresh_scene, 1))
    print(f"MEASURED Add Shader world: Prism / Cycles mean luminance {prism.mean() / cycles.mean():.4f}")
    assert cycles.mean() > 0.5
    assert prism.mean() / cycles.mean() == pytest.approx(1.0, abs=0.02)
