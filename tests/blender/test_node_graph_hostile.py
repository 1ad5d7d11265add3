"""Hostile node graphs: a loop of reroutes is ignored as Cycles ignores it (never followed round and round
by the render or the Material panel), and a tree deeper than the node compiler's limit is refused with
one message naming the material, the node where the limit was hit, the limit and the fix.
"""

from __future__ import annotations

import importlib
import threading

import bpy
import pytest

from helpers.batch_outcome import batch_refusal, batch_warning
from helpers.error_scenes import base_scene


def _module(addon, name):
    return importlib.import_module(f"{addon.__name__}.{name}")


def _export(addon):
    warnings = []
    scene = _module(addon, "engine.export").export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    return scene, warnings


def _export_error(addon) -> str:
    errors = _module(addon, "engine.tracer.errors")
    with pytest.raises(errors.PrismInputError) as caught:
        _export(addon)
    return str(caught.value)


def _within(seconds, function, *args):
    """``function(*args)`` run in a thread that must finish within ``seconds`` (a hang fails the test)."""
    result = {}

    def run():
        try:
            result["value"] = function(*args)
        except Exception as error:  # noqa: BLE001 - handed back to the test
            result["error"] = error

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), f"{getattr(function, '__name__', function)} hung"
    if "error" in result:
        raise result["error"]
    return result.get("value")


def _reroute_loop(material):
    """Material Output ▸ Surface ← Reroute ⇄ Reroute.001: Blender marks one link of the loop invalid."""
    tree = material.node_tree
    first, second = tree.nodes.new("NodeReroute"), tree.nodes.new("NodeReroute")
    tree.links.new(first.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    tree.links.new(second.outputs[0], first.inputs[0])
    tree.links.new(first.outputs[0], second.inputs[0])
    bpy.context.view_layer.update()
    return first, second


def test_a_loop_of_reroutes_is_ignored_by_render_and_panel(prism_addon, fresh_scene, bad_input, capsys, tmp_path):
    base_scene()
    material = bpy.data.materials["Floor material"]
    _reroute_loop(material)
    assert any(not link.is_valid for link in material.node_tree.links)
    principled = _module(prism_addon, "engine.properties.principled")
    assert _within(10, principled.surface_node, material) is None
    reading = _within(10, principled.read_principled, material)
    assert reading.node_name is None
    nodes = _module(prism_addon, "engine.export.nodes")
    preview = _within(10, lambda: nodes.compile_material(material, load_pixels=False))  # the panel's compile
    assert preview.shader is not None and not preview.shader.closures  # Cycles: nothing feeds Surface, black
    scene, warnings = _within(60, _export, prism_addon)
    found = [w for w in warnings if "invalid" in w]
    assert found and found[0].startswith("Material 'Floor material': the link from 'Reroute") and "loop" in found[0]
    bad_input("material whose Surface comes from a loop of two Reroute nodes",
              *batch_warning(capsys, tmp_path, found[0]))


def test_a_loop_of_reroutes_in_a_world_is_ignored(prism_addon, fresh_scene):
    base_scene()
    world = bpy.data.worlds.new("Loop")
    world.use_nodes = True
    tree = world.node_tree
    first, second = tree.nodes.new("NodeReroute"), tree.nodes.new("NodeReroute")
    tree.links.new(first.outputs[0], tree.nodes["Background"].inputs["Color"])
    tree.links.new(second.outputs[0], first.inputs[0])
    tree.links.new(first.outputs[0], second.inputs[0])
    bpy.context.scene.world = world
    bpy.context.view_layer.update()
    scene, _ = _within(60, _export, prism_addon)
    assert scene.world.kind == "constant"


def _math_chain(material, length):
    """Principled Roughness ← Math ← Math.001 ← … (``length`` Add nodes, each adding 0.0001)."""
    tree = material.node_tree
    target = tree.nodes["Principled BSDF"].inputs["Roughness"]
    for _ in range(length):
        node = tree.nodes.new("ShaderNodeMath")
        node.operation = "ADD"
        node.inputs[1].default_value = 0.0001
        tree.links.new(node.outputs[0], target)
        target = node.inputs[0]
    return node


def _mix_chain(material, length):
    """Material Output ▸ Surface ← Mix Shader ← Mix Shader.001 ← … ← Principled BSDF."""
    tree = material.node_tree
    target = tree.nodes["Material Output"].inputs["Surface"]
    for _ in range(length):
        node = tree.nodes.new("ShaderNodeMixShader")
        tree.links.new(node.outputs[0], target)
        target = node.inputs[1]
    tree.links.new(tree.nodes["Principled BSDF"].outputs[0], target)
    return node


def test_a_tree_just_within_the_limit_compiles(prism_addon, fresh_scene):
    base_scene()
    limit = _module(prism_addon, "engine.export.nodes.compiler").MAX_NODE_DEPTH
    _math_chain(bpy.data.materials["Floor material"], limit - 2)  # + the Principled BSDF: within the limit
    scene, _ = _export(prism_addon)
    assert scene.materials


@pytest.mark.parametrize("build, length, description", [
    (_mix_chain, 500, "a chain of 500 Mix Shader nodes"),
    (_math_chain, 1000, "a chain of 1000 Math nodes into Roughness"),
])
def test_a_tree_deeper_than_the_limit_is_refused_naming_node_and_limit(prism_addon, fresh_scene, bad_input, capsys,
                                                                       tmp_path, build, length, description):
    base_scene()
    limit = _module(prism_addon, "engine.export.nodes.compiler").MAX_NODE_DEPTH
    material = bpy.data.materials["Floor material"]
    build(material, length)
    message = _within(60, _export_error, prism_addon)
    assert message.startswith(f"Material 'Floor material': node tree deeper than {limit} nodes at '")
    assert f"Prism compiles trees up to {limit} deep: simplify it" in message
    named = message.split(" at '")[1].split("'")[0]
    assert named in material.node_tree.nodes
    bad_input(description, *batch_refusal(capsys, tmp_path, message))
    # the Material panel's compile says the same, without a traceback
    nodes = _module(prism_addon, "engine.export.nodes")
    errors = _module(prism_addon, "engine.tracer.errors")
    with pytest.raises(errors.PrismInputError, match="deeper than"):
        nodes.compile_material(material, load_pixels=False)
