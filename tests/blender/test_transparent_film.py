"""Film ▸ Transparent, Transparent Glass and holdouts through Blender, against Cycles: the background has
alpha 0 and the objects 1, as in Cycles' render of the same scene; glass lets the background through by
its transmittance with Transparent Glass on; holdouts (an object's Holdout box, the Holdout shader) cut
alpha-0 holes; and the Render Result composites over a plate (Alpha Over) as a premultiplied image."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light
from helpers.cycles import render_cycles_rgba, render_prism_rgba


def _scene(material=None):
    add_plane("Floor", 3.0, color=(0.6, 0.6, 0.6))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(0.0, 0.0, 0.8), segments=32, ring_count=16)
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    if material is None:
        material = bpy.data.materials.new("Red")
        material.use_nodes = True
        material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.1, 0.1, 1.0)
    sphere.data.materials.append(material)
    add_point_light("Bulb", 400.0, (1.0, -1.5, 3.0))
    add_camera((0.0, -4.5, 2.2), (math.radians(70), 0.0, 0.0), lens_mm=35.0, resolution=(40, 30))
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.3, 0.5, 0.8, 1.0)
    bpy.context.scene.world = world
    return sphere


def _glass():
    material = bpy.data.materials.new("Glass")
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Transmission Weight"].default_value = 1.0
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)  # Prism's glass is clear: no tint in Cycles either
    bsdf.inputs["Roughness"].default_value = 0.0
    bsdf.inputs["IOR"].default_value = 1.5
    return material


def _interior(mask):
    """Pixels of ``mask`` whose 8 neighbours are in it too: edge pixels' coverage depends on where each
    renderer's samples fall."""
    padded = np.pad(mask, 1, mode="edge")
    h, w = mask.shape
    return np.all([padded[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)


def test_transparent_film_alpha_matches_cycles_and_composites_over_a_plate(prism_addon, fresh_scene):
    _scene()
    fresh_scene.render.film_transparent = True
    prism = render_prism_rgba(fresh_scene, samples=16)
    cycles = render_cycles_rgba(fresh_scene, samples=16)
    background = _interior(cycles[..., 3] == 0.0)
    assert 0.1 < background.mean() < 0.9
    assert np.all(prism[background, 3] == 0.0) and np.all(prism[background, :3] == 0.0)
    assert np.all(prism[_interior(cycles[..., 3] == 1.0), 3] == 1.0)
    print(f"MEASURED transparent film: {100 * background.mean():.1f} % interior background pixels, mean |alpha "
          f"Prism - Cycles| {np.abs(prism[..., 3] - cycles[..., 3]).mean():.4f}")
    assert np.abs(prism[..., 3] - cycles[..., 3]).mean() < 0.02  # edge pixels' coverage

    # Alpha Over onto an orange plate in the compositor: background pixels become the plate, the rest
    # stays as rendered, edges mix as premultiplied colour over the plate.
    plate = (0.9, 0.5, 0.1)
    fresh_scene.use_nodes = True
    tree = fresh_scene.node_tree
    layers = next(n for n in tree.nodes if n.bl_idname == "CompositorNodeRLayers")
    composite = next(n for n in tree.nodes if n.bl_idname == "CompositorNodeComposite")
    colour = tree.nodes.new("CompositorNodeRGB")
    colour.outputs[0].default_value = (*plate, 1.0)
    over = tree.nodes.new("CompositorNodeAlphaOver")
    tree.links.new(colour.outputs[0], over.inputs[1])
    tree.links.new(layers.outputs["Image"], over.inputs[2])
    tree.links.new(over.outputs[0], composite.inputs["Image"])
    composited = render_prism_rgba(fresh_scene, samples=16)
    expected = prism[..., :3] + (1.0 - prism[..., 3:4]) * np.array(plate)
    print(f"MEASURED Alpha Over: max |composite - (rgb + (1 - alpha) plate)| {np.abs(composited[..., :3] - expected).max():.2e}")
    assert np.allclose(composited[..., :3], expected, atol=2e-3)
    assert np.allclose(composited[background, :3], plate, atol=1e-3)


def _sphere_pixels(scene, centre, radius):
    """Pixels whose corners all see the sphere (centre, radius): rows from the top."""
    camera = scene.camera
    width, height = scene.render.resolution_x, scene.render.resolution_y
    frame = [camera.matrix_world @ v for v in camera.data.view_frame(scene=scene)]  # TR, BR, BL, TL
    eye = np.array(camera.matrix_world.translation)
    top_left, top_right, bottom_left = (np.array(frame[i]) for i in (3, 0, 2))
    u = np.linspace(0.0, 1.0, width + 1)[None, :, None]
    v = np.linspace(0.0, 1.0, height + 1)[:, None, None]
    d = top_left + u * (top_right - top_left) + v * (bottom_left - top_left) - eye
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    oc = eye - np.array(centre)
    b = d @ oc
    hit = b * b - (oc @ oc - radius * radius) > 0.0
    return hit[:-1, :-1] & hit[:-1, 1:] & hit[1:, :-1] & hit[1:, 1:]


@pytest.mark.parametrize("transparent_glass", [False, True])
def test_glass_over_the_background_matches_cycles(prism_addon, fresh_scene, transparent_glass):
    _scene(_glass())
    fresh_scene.render.film_transparent = True
    fresh_scene.cycles.film_transparent_glass = transparent_glass
    prism = render_prism_rgba(fresh_scene, samples=64)
    cycles = render_cycles_rgba(fresh_scene, samples=64, max_bounces=12)
    sphere = _sphere_pixels(fresh_scene, (0.0, 0.0, 0.8), 0.6)  # the sky and the floor behind it, refracted
    print(f"MEASURED glass, transparent glass {transparent_glass}: mean alpha over the sphere Prism "
          f"{prism[sphere, 3].mean():.4f}, Cycles {cycles[sphere, 3].mean():.4f}")
    assert abs(prism[sphere, 3].mean() - cycles[sphere, 3].mean()) < 0.03
    if transparent_glass:
        assert cycles[sphere, 3].min() < 0.5
    else:
        assert np.all(prism[sphere, 3] == 1.0)


def test_holdouts_cut_transparent_holes_as_in_cycles(prism_addon, fresh_scene):
    sphere = _scene()
    sphere.is_holdout = True
    prism = render_prism_rgba(fresh_scene, samples=16)
    cycles = render_cycles_rgba(fresh_scene, samples=16)
    hole = cycles[..., 3] < 1.0
    assert hole.mean() > 0.05 and np.all(prism[_interior(cycles[..., 3] == 0.0), :4] == 0.0)
    assert np.abs(prism[..., 3] - cycles[..., 3]).mean() < 0.02
    # The Holdout shader on an ordinary object: the same hole.
    sphere.is_holdout = False
    holdout = bpy.data.materials.new("Hole")
    holdout.use_nodes = True
    nodes = holdout.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    holdout.node_tree.links.new(nodes.new("ShaderNodeHoldout").outputs[0], nodes["Material Output"].inputs["Surface"])
    sphere.data.materials[0] = holdout
    shader = render_prism_rgba(fresh_scene, samples=16)
    assert np.abs(shader[..., 3] - prism[..., 3]).max() < 1e-6
