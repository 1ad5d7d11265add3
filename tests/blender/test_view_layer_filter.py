"""View Layer ▸ Filter ▸ Surfaces, Curves and Motion Blur, as Cycles' Blender sync reads them: a mesh gets
no triangles with Surfaces off (the world alone renders), hair curves none with Curves off, and motion blur
needs the layer's switch as well as Render ▸ Motion Blur. Absolute comparisons with Cycles for the same
switches are in the parity harness (``tests/blender/test_parity.py``: surfaces_filter, curves_filter,
layer_motion_blur)."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.batch import run_batch
from helpers.bpy_scenes import add_camera, add_plane, add_point_light
from helpers.cycles import luminance, render_prism_rgba

WORLD = 0.5  # the world's radiance (white)


def _export(addon):
    warnings = []
    export = importlib.import_module(f"{addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings), warnings


def _world(strength=WORLD):
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = strength
    bpy.context.scene.world = world


def _tuft():
    """A Curves object of four hairs."""
    curves = bpy.data.hair_curves.new("Tuft")
    curves.add_curves([2] * 4)
    for index, curve in enumerate(curves.curves):
        curve.points[0].position = (0.1 * index, 0.0, 0.0)
        curve.points[1].position = (0.1 * index, 0.0, 1.0)
    obj = bpy.data.objects.new("Tuft", curves)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def test_surfaces_off_renders_the_world_alone(prism_addon, fresh_scene):
    """A card under a bulb and a white world of radiance 0.5, seen from above: with Surfaces off every
    pixel is the world (no card, and the bulb lights nothing); the export has no triangle and no warning."""
    _world()
    add_plane("Card", 1.2, color=(0.8, 0.1, 0.1), specular=0.0)
    add_point_light("Bulb", 50.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(16, 16))
    lit = luminance(render_prism_rgba(fresh_scene, 4))
    bpy.context.view_layer.use_solid = False
    scene, warnings = _export(prism_addon)
    assert scene.triangle_count == 0
    assert not [w for w in warnings if "Surfaces" in w]
    alone = luminance(render_prism_rgba(fresh_scene, 4))
    print(f"MEASURED Surfaces off: mean luminance {alone.mean():.6f} (world {WORLD}), pixels {alone.min():.4f}-"
          f"{alone.max():.4f}; on: card pixel {lit[8, 8]:.4f}")
    assert alone.mean() == pytest.approx(WORLD, rel=1e-3)
    assert np.allclose(alone, WORLD, rtol=0.02)  # the spectral sampling's colour noise of a white world, 4 spp
    assert abs(lit[8, 8] - WORLD) > 0.05  # with the filter on, the card is there


def test_surfaces_off_under_a_black_world_is_refused_naming_the_filter(prism_addon, fresh_scene, tmp_path, capsys,
                                                                       bad_input):
    """Nothing but a black world would be left (Cycles renders black): refused, naming the layer and switch."""
    _world(0.0)
    add_plane("Card", 1.2)
    add_point_light("Bulb", 50.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(16, 16))
    bpy.context.view_layer.use_solid = False
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status == 1
    assert line == (
        "Prism: error: Scene 'Scene' has nothing to render: View Layer 'ViewLayer' ▸ Filter ▸ Surfaces is off, so no "
        "geometry is rendered, and the world is black: turn the filter on, or the image would be black.")
    bad_input("View Layer ▸ Filter ▸ Surfaces off under a black world (nothing left to render)", status, line)


@pytest.mark.parametrize("curves_on", [True, False])
def test_curves_filter_leaves_out_hair_curves_only(prism_addon, fresh_scene, curves_on):
    _world()
    add_plane("Card", 1.2)
    _tuft()
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(16, 16))
    bpy.context.view_layer.use_strand = curves_on
    scene, _ = _export(prism_addon)
    assert ("Tuft" in scene.object_names) is curves_on
    assert "Card" in scene.object_names


@pytest.mark.parametrize("layer_motion_blur", [True, False])
def test_motion_blur_needs_the_view_layers_switch(prism_addon, fresh_scene, layer_motion_blur):
    """Render ▸ Motion Blur on and a moving camera: the shutter is sampled only where the view layer's
    Filter ▸ Motion Blur is on too (Cycles: ``use_motion_blur`` of both)."""
    _world()
    add_plane("Card", 1.2)
    camera = add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(16, 16))
    for frame, x in ((0, -0.5), (2, 0.5)):
        camera.location.x = x
        camera.keyframe_insert("location", index=0, frame=frame)
    fresh_scene.frame_set(1)
    fresh_scene.render.use_motion_blur = True
    bpy.context.view_layer.use_motion_blur = layer_motion_blur
    scene, _ = _export(prism_addon)
    assert (scene.camera.shutter_times is not None) is layer_motion_blur


def test_the_filter_panel_is_shown_for_prism(prism_addon, fresh_scene):
    """Blender's View Layer ▸ Filter panel lists Prism among its engines, so the switches above can be set."""
    assert "PRISM" in bpy.types.VIEWLAYER_PT_filter.COMPAT_ENGINES
