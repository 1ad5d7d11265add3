"""Meshes that change their number of vertices over time, under motion blur and in the Vector pass.

A liquid's surface or Geometry Nodes that add geometry change a mesh's vertices from one time to the next. The
card of ``test_motion_blur`` is made by Geometry Nodes here: a 1 m grid with 2 + 4 × frame columns of vertices (5,
6 and 7 at the shutter's three steps), flying 2 m a frame along x.
With a ``velocity`` attribute saying so (48 m/s at 24 fps) it blurs by it, as Cycles blurs it: the smear's profile
is the closed form's, and its energy Cycles'. Without one it stays still, named in a warning, and only it: a mesh
beside it still blurs. A mesh with a velocity attribute moves by it even where its vertices could be followed, as
Cycles takes the attribute over the steps."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from blender.test_motion_blur import SHUTTER_FRAMES, SPEED_M_PER_FRAME, _box_profile, _moving_card_scene, _profile
from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import linear_keys

FPS = 24
VELOCITY_M_S = SPEED_M_PER_FRAME * FPS


def _node_card(card, columns_per_frame=4.0, flies=True, velocity=True):
    """Replace ``card``'s keyframed flight by Geometry Nodes: a 1 m grid of 2 + ``columns_per_frame`` × frame
    columns, at x = 2 m × (frame - 1) where ``flies``, with the ``velocity`` attribute (48 m/s along x) where
    ``velocity``."""
    card.animation_data_clear()
    card.location = (0.0, 0.0, 0.0)
    tree = bpy.data.node_groups.new("Card", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = tree.nodes, tree.links
    grid, out, time = nodes.new("GeometryNodeMeshGrid"), nodes.new("NodeGroupOutput"), nodes.new(
        "GeometryNodeInputSceneTime")
    grid.inputs["Size X"].default_value = grid.inputs["Size Y"].default_value = 1.0
    grid.inputs["Vertices Y"].default_value = 2
    columns = nodes.new("ShaderNodeMath")
    columns.operation = "MULTIPLY_ADD"
    columns.inputs[1].default_value, columns.inputs[2].default_value = columns_per_frame, 2.0
    links.new(time.outputs["Frame"], columns.inputs[0])
    links.new(columns.outputs[0], grid.inputs["Vertices X"])
    last = grid.outputs["Mesh"]
    if flies:
        along, offset, move = nodes.new("ShaderNodeMath"), nodes.new("ShaderNodeCombineXYZ"), nodes.new(
            "GeometryNodeSetPosition")
        along.operation = "MULTIPLY_ADD"
        along.inputs[1].default_value, along.inputs[2].default_value = SPEED_M_PER_FRAME, -SPEED_M_PER_FRAME
        links.new(time.outputs["Frame"], along.inputs[0])
        links.new(along.outputs[0], offset.inputs["X"])
        links.new(last, move.inputs["Geometry"])
        links.new(offset.outputs[0], move.inputs["Offset"])
        last = move.outputs["Geometry"]
    if velocity:
        store = nodes.new("GeometryNodeStoreNamedAttribute")
        store.data_type, store.domain = "FLOAT_VECTOR", "POINT"
        store.inputs["Name"].default_value = "velocity"
        store.inputs["Value"].default_value = (VELOCITY_M_S, 0.0, 0.0)
        links.new(last, store.inputs["Geometry"])
        last = store.outputs["Geometry"]
    paint = nodes.new("GeometryNodeSetMaterial")
    paint.inputs["Material"].default_value = card.data.materials[0]
    links.new(last, paint.inputs["Geometry"])
    links.new(paint.outputs["Geometry"], out.inputs[0])
    card.modifiers.new("Card", "NODES").node_group = tree
    bpy.context.scene.frame_set(1)


def _export(prism_addon, warnings):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def _card_steps(scene):
    card = scene.triangles[scene.triangle_object == scene.object_names.index("Card")]
    on = np.unique(card)
    return scene.motion.vertices[:, on], scene.vertices[on]


def test_a_changing_mesh_blurs_by_its_velocity_as_the_closed_form_and_cycles(fresh_scene, prism_addon):
    """The card's vertices move by velocity × (step time - frame time), ±0.5 m at the shutter's ends (Center), so
    the smear is the box convolution of the card with its 1 m travel, and Prism's energy is Cycles' within 2 %."""
    card = _moving_card_scene(fresh_scene)
    _node_card(card)
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    steps, frame = _card_steps(scene)
    assert len(frame) == 12  # 6 columns of 2 at the frame
    travel = SPEED_M_PER_FRAME * SHUTTER_FRAMES
    for step, shift in enumerate((-travel / 2, 0.0, travel / 2)):
        np.testing.assert_allclose(steps[step], frame + [shift, 0.0, 0.0], atol=1e-9)
    prism = render_prism_rgba(fresh_scene, 32, seed=1)[..., :3].astype(np.float64)
    cycles = render_cycles_rgba(fresh_scene, 32, seed=1, max_bounces=1)[..., :3].astype(np.float64)
    expected = _box_profile(0.0)
    closed, energy = np.abs(_profile(prism) - expected).max(), prism.sum() / cycles.sum()
    difference = np.abs(_profile(prism) - _profile(cycles)).max()
    print(f"MEASURED a changing mesh moved by its velocity: closed form {closed:.4f}, Prism / Cycles energy "
          f"{energy:.4f}, profiles {difference:.4f}")
    assert closed < 0.05, np.round(np.c_[_profile(prism), expected][10:38], 3)
    assert energy == pytest.approx(1.0, abs=0.02)
    assert difference < 0.05
    assert (_profile(cycles) > 0.02).sum() >= 14  # Cycles blurred it too: the sharp card spans 8 columns


def test_a_changing_mesh_without_velocity_stays_still_warned_and_alone(fresh_scene, prism_addon, bad_input):
    """Without the attribute the card cannot be followed: still at the frame, named; a keyframed mesh beside it
    still blurs (before, one such mesh left every mesh of the scene sharp)."""
    card = _moving_card_scene(fresh_scene)
    _node_card(card, velocity=False)
    mover = bpy.data.objects.new("Mover", card.data.copy())
    fresh_scene.collection.objects.link(mover)
    for frame, y in ((0, -1.0), (2, 1.0)):
        mover.location = (0.0, y, 0.0)
        mover.keyframe_insert("location", frame=frame)
    linear_keys(mover)
    fresh_scene.frame_set(1)
    warnings = []
    scene = _export(prism_addon, warnings)
    message = ("Object 'Card': its number of vertices changes during the shutter (geometry added or removed over "
               "time) and it has no 'velocity' attribute, so Prism cannot follow its vertices: it is rendered still "
               "where it is at the frame, without motion blur (as Cycles renders it).")
    assert warnings == [message]
    steps, frame = _card_steps(scene)
    np.testing.assert_array_equal(steps, np.broadcast_to(frame, steps.shape))
    moving = np.unique(scene.triangles[scene.triangle_object == scene.object_names.index("Mover")])
    np.testing.assert_allclose(scene.motion.vertices[2, moving, 1] - scene.motion.vertices[0, moving, 1], 0.5)
    bad_input("a mesh whose number of vertices changes during the shutter and that has no velocity attribute, with "
              "Render ▸ Motion Blur on (a warning; the render goes on)", 0, message)


def test_a_mesh_with_velocity_moves_by_it_even_where_its_vertices_could_be_followed(fresh_scene, prism_addon):
    """A still card of constant topology whose velocity says 48 m/s: Cycles takes the attribute over the steps, so
    Prism does (±0.5 m); with Object ▸ Motion Blur off it stays still."""
    card = _moving_card_scene(fresh_scene)
    _node_card(card, columns_per_frame=0.0, flies=False)
    scene = _export(prism_addon, [])
    steps, frame = _card_steps(scene)
    np.testing.assert_allclose(steps[2] - steps[0], np.broadcast_to([1.0, 0.0, 0.0], frame.shape), atol=1e-9)
    card.cycles.use_motion_blur = False
    assert _export(prism_addon, []).motion is None


def test_a_mesh_moved_by_its_velocity_is_carried_by_its_moving_transform_as_cycles(fresh_scene, prism_addon):
    """The still card of constant topology whose velocity says 48 m/s along x, its object keyed to slide 2 m a frame
    along y: the vertices move ±0.5 m along x by the attribute and ±0.5 m along y with the object, as Cycles adds
    the object's transform motion to its velocity's; Prism's diagonal smear holds Cycles' energy within 2 %, and
    its profiles across and along the image (mean of each row and of each column) are Cycles' within 0.05 (64 spp),
    where the card moved by its velocity alone smears along x only."""
    card = _moving_card_scene(fresh_scene)
    _node_card(card, columns_per_frame=0.0, flies=False)
    for frame, y in ((0, -SPEED_M_PER_FRAME), (2, SPEED_M_PER_FRAME)):
        card.location = (0.0, y, 0.0)
        card.keyframe_insert("location", frame=frame)
    linear_keys(card)
    fresh_scene.frame_set(1)
    scene = _export(prism_addon, [])
    steps, frame = _card_steps(scene)
    np.testing.assert_allclose(steps[2] - steps[0], np.broadcast_to([1.0, 1.0, 0.0], frame.shape), atol=1e-9)
    prism = render_prism_rgba(fresh_scene, 64, seed=1)[..., 1].astype(np.float64)
    cycles = render_cycles_rgba(fresh_scene, 64, seed=1, max_bounces=1)[..., 1].astype(np.float64)
    energy = prism.sum() / cycles.sum()
    rows, columns = (float(np.abs(prism.mean(axis=a) - cycles.mean(axis=a)).max()) for a in (1, 0))
    print(f"MEASURED a velocity card on a moving object: Prism / Cycles energy {energy:.4f}, profiles: rows "
          f"{rows:.4f}, columns {columns:.4f}")
    assert energy == pytest.approx(1.0, abs=0.02)
    assert rows < 0.05 and columns < 0.05
    outside = np.r_[cycles[:4], cycles[-4:]].sum() / cycles.sum()  # rows beyond the card's own 1 m at the frame
    assert outside > 0.1  # Cycles smeared it along y too (a quarter of the light for this travel)


def test_the_vector_pass_follows_a_changing_mesh_by_its_velocity(fresh_scene, prism_addon):
    """Vector pass (motion blur off): one frame's worth each way, 2 m, as Cycles' pass reads the attribute."""
    card = _moving_card_scene(fresh_scene)
    _node_card(card)
    fresh_scene.render.use_motion_blur = False
    fresh_scene.view_layers[0].use_pass_vector = True
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    card_triangles = scene.triangle_object == scene.object_names.index("Card")
    motion = scene.data_passes.triangle_motion[card_triangles]  # [T, 2 frames, 3 corners, xyz]
    np.testing.assert_allclose(motion[:, 0, :, 0], -SPEED_M_PER_FRAME, atol=1e-5)
    np.testing.assert_allclose(motion[:, 1, :, 0], SPEED_M_PER_FRAME, atol=1e-5)
    np.testing.assert_allclose(motion[..., 1:], 0.0, atol=1e-6)
