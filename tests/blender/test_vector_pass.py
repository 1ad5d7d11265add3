"""The Vector pass through Blender (View Layer ▸ Passes ▸ Data ▸ Vector), against Cycles 4.5 on the same
.blend: a card that slides, turns and grows between frames, seen by a camera that moves too, over a still
floor. Cycles' meaning: X, Y = where the surface was in the previous frame - where it is now, Z, W = now -
where it will be in the next frame, in pixels, y up; 0 with Render ▸ Motion Blur on."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from blender.test_passes import _cycles, _render_layers, _switch_on
from helpers.bpy_scenes import add_camera, add_plane, add_point_light

FRAME = 5


def _keyframes(target, path, values):
    """``target.<path>`` keyed at FRAME - 1, FRAME, FRAME + 1 to ``values``, linear in between."""
    for offset, value in zip((-1, 0, 1), values):
        setattr(target, path, value)
        target.keyframe_insert(path, frame=FRAME + offset)
    for curve in target.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"


@pytest.fixture
def moving_scene(fresh_scene):
    scene = fresh_scene
    scene.render.use_compositing = False
    add_plane("Floor", 8.0, color=(0.5, 0.5, 0.5))
    add_plane("Card", 1.2, color=(0.8, 0.3, 0.1), location=(0.0, 0.0, 0.5))
    add_point_light("Bulb", 400.0, (0.5, 0.5, 4.0))
    camera = add_camera((0.0, 0.0, 6.0), (0.0, 0.0, 0.0), resolution=(32, 32))
    card = bpy.data.objects["Card"]
    _keyframes(card, "location", [(-0.15, 0.1, 0.5), (0.0, 0.0, 0.5), (0.3, -0.2, 0.5)])
    _keyframes(card, "rotation_euler", [(0.0, 0.0, -0.2), (0.0, 0.0, 0.0), (0.0, 0.0, 0.3)])
    _keyframes(card, "scale", [(0.9, 0.9, 1.0), (1.0, 1.0, 1.0), (1.2, 1.0, 1.0)])
    _keyframes(camera, "location", [(0.0, 0.0, 6.0), (0.0, 0.0, 6.0), (0.2, 0.1, 6.3)])
    bpy.data.objects["Card"].pass_index = 1
    scene.frame_set(FRAME)
    scene.prism.samples = scene.prism.samples_per_pass = 16
    _switch_on(scene, ("vector", "object_index", "z"))
    return scene


def _inside(index):
    """Pixels whose 3 x 3 neighbourhood sees one object (no edge between surfaces in the pixel's filter)."""
    same = np.zeros(index.shape[:2], bool)
    same[1:-1, 1:-1] = np.all([index[1:-1, 1:-1, 0] == np.roll(np.roll(index, dy, 0), dx, 1)[1:-1, 1:-1, 0]
                               for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)
    return same


def test_vector_pass_matches_cycles(prism_addon, moving_scene, tmp_path):
    prism = _render_layers(prism_addon, moving_scene, tmp_path / "prism.exr")
    assert moving_scene.frame_current == FRAME  # the export set the frame back
    _cycles(moving_scene)
    moving_scene.cycles.samples = 16
    cycles = _render_layers(prism_addon, moving_scene, tmp_path / "cycles.exr", engine="CYCLES")
    p, c = prism["Vector"], cycles["Vector"]  # X, Y, Z, W
    inside = _inside(cycles["IndexOB"]) & _inside(prism["IndexOB"])
    card = inside & (cycles["IndexOB"][..., 0] == 1)
    floor = inside & (cycles["IndexOB"][..., 0] == 0)
    assert card.sum() > 20 and floor.sum() > 100
    # The card moves by a pixel or more each way; the floor moves with the camera only.
    assert np.abs(c[card]).max() > 1.0 and np.abs(c[floor, 2:]).max() > 0.5 and np.abs(c[floor, :2]).max() < 1e-4
    error = np.abs(p - c)[card | floor]
    assert error.max() < 0.02, (error.max(), np.unravel_index(np.argmax(np.abs(p - c) * (card | floor)[..., None]),
                                                              p.shape))


def test_vector_pass_is_zero_with_motion_blur_on_as_cycles(prism_addon, moving_scene, tmp_path):
    moving_scene.render.use_motion_blur = True
    prism = _render_layers(prism_addon, moving_scene, tmp_path / "prism.exr")
    _cycles(moving_scene)
    moving_scene.cycles.samples = 4
    cycles = _render_layers(prism_addon, moving_scene, tmp_path / "cycles.exr", engine="CYCLES")
    assert np.all(cycles["Vector"] == 0.0)
    assert np.all(prism["Vector"] == 0.0)


def test_vector_pass_of_a_panoramic_camera_is_warned(prism_addon, moving_scene):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    camera = moving_scene.camera.data
    camera.type = "PANO"
    camera.panorama_type = "EQUIRECTANGULAR"
    warnings: list[str] = []
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert scene.data_passes.triangle_motion is None
    assert any("the Vector pass of a panoramic camera ('Camera') is not written by Prism: the pass holds 0" in w
               for w in warnings), warnings


def test_vector_pass_is_read_only_when_asked(prism_addon, moving_scene):
    """Off, the scene is not evaluated at other frames and the kernels get no motion tables."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    moving_scene.view_layers[0].use_pass_vector = False
    frames = []
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), [], frame_set=lambda f, s: frames.append(f))
    assert scene.data_passes.triangle_motion is None and frames == []
    moving_scene.view_layers[0].use_pass_vector = True
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), [])
    assert scene.data_passes.triangle_motion.shape == (len(scene.triangles), 2, 3, 3)
    assert not math.isnan(float(scene.data_passes.world_to_raster.sum()))


def test_vector_pass_of_a_real_lens_camera_is_warned(prism_addon, moving_scene):
    """A real lens's distortion is not in the projection: said, and the pass is still written."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    vector_pass = importlib.import_module(f"{prism_addon.__name__}.engine.export.vector_pass")
    depsgraph = bpy.context.evaluated_depsgraph_get()
    tracer_scene = export.export_scene(depsgraph, [])
    moving_scene.camera.data.prism.lens_model = "REAL_LENS"
    warnings: list[str] = []
    vector_pass.export_vector_pass(moving_scene, depsgraph, tracer_scene, lambda f, s: moving_scene.frame_set(
        f, subframe=s), lambda evaluated: export.export_meshes(evaluated, None), warnings,
        export.export_meshes(depsgraph, None))
    assert any("the Vector pass of camera 'Camera' is projected through Blender's camera (a pinhole of its focal "
               "length), not through its real lens" in w for w in warnings), warnings
    assert tracer_scene.data_passes.triangle_motion is not None
