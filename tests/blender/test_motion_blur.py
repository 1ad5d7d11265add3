"""Motion blur through Blender: an emitting card keyframed to cross the view at constant speed, seen by an
orthographic camera over a black world. The smear is the box convolution of the card with its travel
(speed × Shutter) placed where Render ▸ Motion Blur ▸ Position puts the shutter (Start: from the frame on,
Center: around it, End: up to it), Prism's image matches Cycles' in absolute light, the export leaves
the user's frame as it was, and the settings Prism does not follow are named."""

from __future__ import annotations

import importlib
import os

import bpy
import numpy as np
import pytest

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import linear_keys

PIXELS_X, PIXELS_Y, VIEW_M = 48, 16, 6.0  # 1/8 m a pixel
SPEED_M_PER_FRAME, SHUTTER_FRAMES = 2.0, 0.5  # travel while open: 1 m, 8 px
SIDE_M = 1.0


def _emission(name, strength=1.0):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = strength
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs[0], output.inputs["Surface"])
    return material


def _moving_card_scene(scene):
    half = SIDE_M / 2
    mesh = bpy.data.meshes.new("Card")
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(_emission("glow"))
    card = bpy.data.objects.new("Card", mesh)
    scene.collection.objects.link(card)
    for frame, x in ((0, -SPEED_M_PER_FRAME), (2, SPEED_M_PER_FRAME)):  # x = 0 at frame 1
        card.location = (x, 0.0, 0.0)
        card.keyframe_insert("location", frame=frame)
    linear_keys(card)
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (0.0, 0.0, 5.0)
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = VIEW_M
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = PIXELS_X, PIXELS_Y, 100
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = SHUTTER_FRAMES
    scene.frame_set(1)
    return card


def _profile(image):
    """Mean green of the rows well inside the card (its 8 middle px span rows 4..11), per column."""
    return image[5:11, :, 1].mean(axis=0)


def _box_profile(centre_shift_m):
    """Closed form per column: the card's indicator convolved with a box of the travel, whose middle lies
    ``centre_shift_m`` right of the card's place at the frame, averaged over each pixel."""
    travel = SPEED_M_PER_FRAME * SHUTTER_FRAMES
    edges = (np.arange(PIXELS_X + 1) / PIXELS_X - 0.5) * VIEW_M
    x = edges[:-1, None] + np.diff(edges)[:, None] * ((np.arange(200) + 0.5) / 200)[None, :]
    centres = centre_shift_m + travel * ((np.arange(400) + 0.5) / 400 - 0.5)  # the card's centre over τ
    return (np.abs(x[..., None] - centres) <= SIDE_M / 2).mean(axis=(1, 2))


@pytest.mark.parametrize("position, shift_m", [("START", 0.5), ("CENTER", 0.0), ("END", -0.5)])
def test_the_shutter_position_places_the_smear_as_blender_defines(fresh_scene, position, shift_m):
    _moving_card_scene(fresh_scene)
    fresh_scene.render.motion_blur_position = position
    profile = _profile(render_prism_rgba(fresh_scene, 32, seed=1).astype(np.float64))
    expected = _box_profile(shift_m)
    assert np.abs(profile - expected).max() < 0.05, np.round(np.c_[profile, expected][10:38], 3)
    columns = (np.arange(PIXELS_X) + 0.5) / PIXELS_X * VIEW_M - VIEW_M / 2
    centroid = (profile * columns).sum() / profile.sum()
    assert centroid == pytest.approx(shift_m, abs=0.03)
    assert fresh_scene.frame_current == 1 and fresh_scene.frame_subframe == 0.0  # the user's frame, untouched


def test_the_smear_matches_cycles_in_absolute_light(fresh_scene):
    _moving_card_scene(fresh_scene)
    fresh_scene.render.motion_blur_position = "START"
    prism = render_prism_rgba(fresh_scene, 64, seed=1)[..., :3].astype(np.float64)
    cycles = render_cycles_rgba(fresh_scene, 64, seed=1, max_bounces=1)[..., :3].astype(np.float64)
    energy = prism.sum() / cycles.sum()
    difference = np.abs(_profile(prism) - _profile(cycles)).max()
    if os.environ.get("PRISM_DOC_IMAGES"):  # docs/motion_blur.md's picture: Prism left, Cycles right
        _save_side_by_side(prism, cycles, os.environ["PRISM_DOC_IMAGES"], energy, difference)
    assert energy == pytest.approx(1.0, abs=0.02)
    assert difference < 0.05, np.round(np.c_[_profile(prism), _profile(cycles)][10:38], 3)
    assert _profile(cycles).max() > 0.95  # Cycles blurred it too (a plateau of 1 and ramps)


def _camera_moves_instead(scene, card):
    """The card stands at x = 0; the camera flies at the card's speed the other way (the same smear)."""
    card.animation_data_clear()
    card.location = (0.0, 0.0, 0.0)
    camera = scene.camera
    for frame, x in ((0, SPEED_M_PER_FRAME), (2, -SPEED_M_PER_FRAME)):
        camera.location = (x, 0.0, 5.0)
        camera.keyframe_insert("location", frame=frame)
    linear_keys(camera)


def _card_deforms_instead(scene, card):
    """The card's object stands still; a shape key carries its vertices across (deformation motion)."""
    card.animation_data_clear()
    card.location = (0.0, 0.0, 0.0)
    card.shape_key_add(name="Basis")
    slide = card.shape_key_add(name="Slide")
    for point, base in zip(slide.data, card.data.shape_keys.key_blocks["Basis"].data):
        point.co = (base.co[0] + SPEED_M_PER_FRAME, base.co[1], base.co[2])
    for point in card.data.shape_keys.key_blocks["Basis"].data:
        point.co = (point.co[0] - SPEED_M_PER_FRAME, point.co[1], point.co[2])
    for frame, value in ((0, 0.0), (2, 1.0)):
        slide.value = value
        slide.keyframe_insert("value", frame=frame)
    linear_keys(card.data.shape_keys)


@pytest.mark.parametrize("motion", [_camera_moves_instead, _card_deforms_instead])
def test_camera_motion_and_deformation_smear_as_the_moving_card_and_as_cycles(fresh_scene, motion):
    card = _moving_card_scene(fresh_scene)
    motion(fresh_scene, card)
    fresh_scene.frame_set(1)
    prism = render_prism_rgba(fresh_scene, 32, seed=1)[..., :3].astype(np.float64)
    cycles = render_cycles_rgba(fresh_scene, 32, seed=1, max_bounces=1)[..., :3].astype(np.float64)
    expected = _box_profile(0.0)
    closed, energy = np.abs(_profile(prism) - expected).max(), prism.sum() / cycles.sum()
    difference = np.abs(_profile(prism) - _profile(cycles)).max()
    print(f"{motion.__name__}: closed form {closed:.4f}, Prism / Cycles energy {energy:.4f}, profiles {difference:.4f}")
    assert closed < 0.05, np.round(np.c_[_profile(prism), expected][10:38], 3)
    assert energy == pytest.approx(1.0, abs=0.02)
    assert difference < 0.05


def test_a_moving_emitter_lights_a_floor_as_cycles_lights_it(fresh_scene):
    """The glowing card (strength 10) flies over a grey floor 1 m below it, seen from under the card (the camera
    0.5 m over the floor, looking down): the light it casts is blurred along its travel in both renderers, Prism
    sampling the card where it is at each ray's time as Cycles does: total light within 2 % of Cycles', the
    floor's profile along the flight within 3 % of Cycles' brightest column, where the card held still (Motion
    Blur off) lights a profile further from Cycles'."""
    card = _moving_card_scene(fresh_scene)
    card.data.materials[0].node_tree.nodes["Emission"].inputs["Strength"].default_value = 10.0
    floor_mesh = bpy.data.meshes.new("Floor")
    floor_mesh.from_pydata([(-6, -6, -1), (6, -6, -1), (6, 6, -1), (-6, 6, -1)], [], [(0, 1, 2, 3)])
    grey = bpy.data.materials.new("Grey")
    grey.diffuse_color = (0.5, 0.5, 0.5, 1.0)
    floor_mesh.materials.append(grey)
    fresh_scene.collection.objects.link(bpy.data.objects.new("Floor", floor_mesh))
    fresh_scene.camera.location = (0.0, 0.0, -0.5)
    fresh_scene.camera.data.clip_start = 0.1
    fresh_scene.frame_set(1)
    prism = render_prism_rgba(fresh_scene, 128, seed=1)[..., :3].astype(np.float64)
    cycles = render_cycles_rgba(fresh_scene, 128, seed=1, max_bounces=1)[..., :3].astype(np.float64)
    fresh_scene.render.use_motion_blur = False
    held = render_prism_rgba(fresh_scene, 128, seed=1)[..., :3].astype(np.float64)
    profiles = [image[..., 1].mean(axis=0) for image in (prism, cycles, held)]
    energy = prism.sum() / cycles.sum()
    difference = np.abs(profiles[0] - profiles[1]).max() / profiles[1].max()
    held_difference = np.abs(profiles[2] - profiles[1]).max() / profiles[1].max()
    print(f"MEASURED a moving emitter lighting a floor: Prism / Cycles light {energy:.4f}, profile difference "
          f"{difference:.4f} of the brightest column; the card held still: {held_difference:.4f}")
    assert energy == pytest.approx(1.0, abs=0.02)
    assert difference < 0.03
    assert held_difference > 2 * difference


def _save_side_by_side(prism, cycles, path, energy, difference):
    gap = np.zeros((prism.shape[0], 2, 3))
    pixels = np.concatenate([prism, gap, cycles], axis=1)
    pixels = np.repeat(np.repeat(pixels, 8, axis=0), 8, axis=1)
    height, width = pixels.shape[:2]
    image = bpy.data.images.new("side_by_side", width, height, alpha=True, float_buffer=False)
    rgba = np.concatenate([np.clip(pixels, 0.0, 1.0) ** (1 / 2.2), np.ones((height, width, 1))], axis=-1)
    image.pixels.foreach_set(rgba[::-1].astype(np.float32).ravel())
    image.filepath_raw, image.file_format = path, "PNG"
    image.save()
    print(f"motion blur: Prism / Cycles energy {energy:.4f}, largest profile difference {difference:.4f}")


def test_export_evaluates_the_shutter_and_names_what_it_does_not_follow(fresh_scene, prism_addon, bad_input):
    card = _moving_card_scene(fresh_scene)
    card.cycles.motion_steps = 2  # 5 time steps
    fresh_scene.cycles.rolling_shutter_type = "TOP"
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    warnings = []
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert fresh_scene.frame_current == 1 and fresh_scene.frame_subframe == 0.0
    steps = scene.motion.vertices
    assert steps.shape == (5, 4, 3)
    # Center: the card's x runs from -0.5 m to +0.5 m over the five steps
    np.testing.assert_allclose(steps[:, :, 0].mean(axis=1), np.linspace(-0.5, 0.5, 5), atol=1e-6)
    assert scene.camera.motion_to_world is None  # the camera stands still
    np.testing.assert_array_equal(scene.camera.shutter_times, [0.0, 1.0])  # the default curve is flat
    shown = [w for w in warnings if "Rolling Shutter" in w]
    assert len(shown) == 1 and "global shutter" in shown[0], warnings
    bad_input("Render ▸ Motion Blur ▸ Rolling Shutter on (a warning; a global shutter)", 0, shown[0])
    card.cycles.use_motion_blur = False  # Object ▸ Motion Blur off: rendered still, as Cycles does
    still = export.export_scene(bpy.context.evaluated_depsgraph_get(), [])
    assert still.motion is None
