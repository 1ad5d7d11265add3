"""Shader AOVs fed by node links (View Layer ▸ Shader AOV, an AOV Output node in the material), against
Cycles 4.5 on the same .blend: a colour AOV from the UV map, a value AOV from a texture, one folded to a
constant, and the pass off where a material has no AOV Output of that name."""

from __future__ import annotations

import bpy
import numpy as np

from blender.test_passes import _cycles, _render_layers
from helpers.bpy_scenes import add_camera, add_plane, add_point_light


def _aov_layer(scene, name, kind):
    aov = scene.view_layers[0].aovs.add()
    aov.name, aov.type = name, kind


def _aov_material(material):
    """AOV Outputs on ``material``: "uv" (Color) ← Texture Coordinate ▸ UV, "stripes" (Value) ← a Wave
    texture's Fac, "folded" (Value) ← a Math node of two constants (2 × 3.5)."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    coordinates = nodes.new("ShaderNodeTexCoord")
    uv_out = nodes.new("ShaderNodeOutputAOV")
    uv_out.aov_name = "uv"
    links.new(coordinates.outputs["UV"], uv_out.inputs["Color"])
    wave = nodes.new("ShaderNodeTexWave")
    wave.inputs["Scale"].default_value = 2.0
    links.new(coordinates.outputs["UV"], wave.inputs["Vector"])
    stripes = nodes.new("ShaderNodeOutputAOV")
    stripes.aov_name = "stripes"
    links.new(wave.outputs["Fac"], stripes.inputs["Value"])
    product = nodes.new("ShaderNodeMath")
    product.operation = "MULTIPLY"
    product.inputs[0].default_value, product.inputs[1].default_value = 2.0, 3.5
    folded = nodes.new("ShaderNodeOutputAOV")
    folded.aov_name = "folded"
    links.new(product.outputs[0], folded.inputs["Value"])


def test_linked_aovs_match_cycles(prism_addon, fresh_scene, tmp_path):
    scene = fresh_scene
    scene.render.use_compositing = False
    card = add_plane("Card", 2.0, color=(0.8, 0.3, 0.1))
    card.data.uv_layers.new(name="UVMap").data.foreach_set("uv", [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0])
    _aov_material(card.active_material)
    add_plane("Floor", 8.0, location=(0.0, 0.0, -0.5))  # no AOV Output: its AOV pixels are 0
    add_point_light("Bulb", 300.0, (0.3, 0.2, 3.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(32, 24))
    for name, kind in (("uv", "COLOR"), ("stripes", "VALUE"), ("folded", "VALUE")):
        _aov_layer(scene, name, kind)
    scene.prism.samples = scene.prism.samples_per_pass = 64
    prism = _render_layers(prism_addon, scene, tmp_path / "prism.exr")
    _cycles(scene)
    scene.cycles.samples = 64
    cycles = _render_layers(prism_addon, scene, tmp_path / "cycles.exr", engine="CYCLES")
    # Pixels wholly on the card (the card spans ±1 m of the view's ±1.44 m at 4 m: columns 5-26, rows 5-18)
    # and wholly off it (the floor beside it).
    card_px, floor_px = (slice(6, 18), slice(7, 25)), (slice(None), slice(0, 3))
    uv_error = np.abs(prism["uv"][card_px][..., :3] - cycles["uv"][card_px][..., :3])
    stripes_error = np.abs(prism["stripes"][card_px] - cycles["stripes"][card_px])
    print(f"MEASURED uv max error {uv_error.max():.4f}, stripes 95 % {np.percentile(stripes_error, 95):.4f} (range {cycles['uv'][card_px][..., :2].min():.3f}-"
          f"{cycles['uv'][card_px][..., :2].max():.3f}); stripes max error {stripes_error.max():.4f} (range "
          f"{cycles['stripes'][card_px].min():.3f}-{cycles['stripes'][card_px].max():.3f}); folded "
          f"{float(prism['folded'][card_px].mean()):.4f}")
    assert cycles["uv"][card_px][..., 0].max() - cycles["uv"][card_px][..., 0].min() > 0.5  # it varies
    assert uv_error.max() < 0.01
    # A pixel's mean of a steep texture over 16 samples: the sample positions differ between the engines.
    assert np.ptp(cycles["stripes"][card_px]) > 0.5
    assert np.percentile(stripes_error, 95) < 0.02 and stripes_error.max() < 0.06
    assert np.allclose(prism["folded"][card_px], 7.0) and np.allclose(cycles["folded"][card_px], 7.0)
    for name in ("uv", "stripes", "folded"):
        assert np.all(prism[name][floor_px] == 0.0) and np.all(cycles[name][floor_px] == 0.0), name


def test_a_linked_aov_is_not_warned_any_more(prism_addon, fresh_scene):
    from importlib import import_module

    export = import_module(f"{prism_addon.__name__}.engine.export.materials")
    card = add_plane("Card", 2.0)
    _aov_material(card.active_material)
    warnings: list[str] = []
    material = export.export_material(card.active_material, warnings)
    assert not any("AOV" in w for w in warnings), warnings
    assert set(material.shader.aov_registers) == {"uv", "stripes"} and material.aovs["folded"][3] == 7.0
