"""A material whose node tree has no Material Output (an add-on's tree, the add-on not installed)
renders black, as Cycles renders it and as Prism's warning says."""

from __future__ import annotations

import importlib

import bpy

from helpers.bpy_scenes import add_camera, add_plane, add_point_light
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world


def test_material_without_output_renders_black_as_in_cycles(prism_addon, fresh_scene, tmp_path):
    """Left half: a grey card (the control, lit); right half: a card whose tree lost its output. Cycles
    and Prism: the orphaned card's mean luminance is 0 (the control's is about 0.1)."""
    black_world()
    lost = add_plane("Lost", 1.0, location=(0.55, 0.0, 0.0))
    tree = lost.data.materials[0].node_tree
    tree.nodes.remove(tree.nodes["Material Output"])
    add_plane("Control", 1.0, location=(-0.55, 0.0, 0.0))
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(32, 16))
    warnings = []
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert [w for w in warnings if "Lost" in w] == [
        "Material 'Lost material': has no Material Output for Cycles; Prism renders it black."]
    cycles = luminance(render_cycles_rgba(fresh_scene, 4))
    prism = luminance(render_prism_rgba(fresh_scene, 4))
    for image in (cycles, prism):
        assert image[4:12, 2:14].mean() > 0.05  # the control, lit
        assert image[4:12, 18:30].mean() == 0.0  # the card without an output: black
