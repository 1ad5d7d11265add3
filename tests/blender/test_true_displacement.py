"""Material ▸ Settings ▸ Displacement "Displacement Only" and "Both": the vertices move, as Cycles 4.5 moves them,
rendered by Prism and by Cycles from the same .blend and compared in absolute light and with closed forms."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_point_light
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

SAMPLES = 16


def _displaced_material(name, method, height_node=None, height=1.0, midlevel=0.0, scale=0.3):
    """A grey Diffuse BSDF whose Material Output's Displacement is a Displacement node (``height`` or the Fac of
    a texture node ``height_node``), with Material ▸ Settings ▸ Displacement ``method``."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.displacement_method = method
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.5, 0.5, 0.5, 1.0)
    links.new(diffuse.outputs[0], nodes["Material Output"].inputs["Surface"])
    displacement = nodes.new("ShaderNodeDisplacement")
    displacement.inputs["Height"].default_value = height
    displacement.inputs["Midlevel"].default_value = midlevel
    displacement.inputs["Scale"].default_value = scale
    if height_node is not None:
        texture = nodes.new(height_node)
        links.new(texture.outputs["Fac"], displacement.inputs["Height"])
    links.new(displacement.outputs[0], nodes["Material Output"].inputs["Displacement"])
    return material


def _grid(name, size, subdivisions, material, smooth=False):
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=subdivisions, y_subdivisions=subdivisions, size=size)
    grid = bpy.context.active_object
    grid.name = name
    grid.data.materials.append(material)
    if smooth:
        bpy.ops.object.shade_smooth()
    return grid


def _black_world(scene):
    """A black world, and Max Bounces 1 as the Cycles renders here have (whose per-kind limits, 1 too, stay set on
    the scene once Cycles has rendered it, and Prism reads them)."""
    scene.world = bpy.data.worlds.new("Black")
    scene.world.color = (0.0, 0.0, 0.0)
    scene.prism.max_bounces = 1


def test_a_uniform_displacement_lifts_the_plane_to_its_closed_form(prism_addon, fresh_scene):
    """A plane under a point light 2 m up, seen straight down by an orthographic camera (a pixel sees the same
    x, y whatever the plane's height), displaced by Height 1 × Scale 0.3 along its normal: it rises to 0.3 m,
    and the light on it grows by (2 / 1.7)². Scaled by 2 (object space, as Cycles reads it) it rises 0.6 m:
    (2 / 1.4)². Both against Cycles too; with Bump Only (Blender's default) nothing moves."""
    _black_world(fresh_scene)
    material = _displaced_material("Lift", "BUMP")
    plane = _grid("Plane", 4.0, 4, material)
    add_point_light("Bulb", 200.0, (0.0, 0.0, 2.0))
    camera = add_camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), resolution=(12, 12))
    camera.data.type, camera.data.ortho_scale = "ORTHO", 0.2
    still = luminance(render_prism_rgba(fresh_scene, SAMPLES)).mean()
    material.displacement_method = "DISPLACEMENT"
    lifted = luminance(render_prism_rgba(fresh_scene, SAMPLES)).mean()
    lifted_cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=1)).mean()
    plane.scale = (2.0, 2.0, 2.0)
    doubled = luminance(render_prism_rgba(fresh_scene, SAMPLES)).mean()
    doubled_cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=1)).mean()
    print(f"MEASURED lifted plane: x{lifted / still:.4f} (closed form {(2 / 1.7) ** 2:.4f}), Cycles "
          f"{lifted / lifted_cycles:.4f}; scaled by 2: x{doubled / still:.4f} (closed form {(2 / 1.4) ** 2:.4f}), "
          f"Cycles {doubled / doubled_cycles:.4f}")
    assert lifted / still == pytest.approx((2.0 / 1.7) ** 2, rel=0.01)
    assert doubled / still == pytest.approx((2.0 / 1.4) ** 2, rel=0.01)
    assert lifted == pytest.approx(lifted_cycles, rel=0.02)
    assert doubled == pytest.approx(doubled_cycles, rel=0.02)


def _model_the_ridges(grid, material):
    """Move ``grid``'s vertices where Blender's Wave texture (bands along X, sine, scale 5) at their Generated
    coordinate puts them (midlevel 0.5, scale 0.15 m, along +Z), and make its material Bump Only: the mesh a
    displacement of these ridges models, for renders without displacement (its link removed)."""
    co = np.empty(len(grid.data.vertices) * 3)
    grid.data.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    generated = (co[:, 0] + 1.0) / 2.0  # the 2 m grid spans its texture space
    co[:, 2] = (0.5 + 0.5 * np.sin(generated * 5.0 * 20.0 - np.pi / 2) - 0.5) * 0.15
    grid.data.vertices.foreach_set("co", co.ravel())
    grid.data.update()
    output = material.node_tree.nodes["Material Output"].inputs["Displacement"]
    for link in list(output.links):
        material.node_tree.links.remove(link)


@pytest.mark.parametrize("smooth", [False, True])
def test_a_textured_displacement_is_the_mesh_it_models(prism_addon, fresh_scene, smooth):
    """A fine grid displaced by a Wave texture (ridges 0.15 m high) under a low sun, seen at a slant, against the
    same ridges modelled as vertices, in Prism and in Cycles: Prism's displaced image is its modelled one (mean
    within 0.5 %, pixel by pixel within 2 % of the mean), Prism / Cycles is the same with displacement as
    without (within 1 %), and within 1.5 % of 1 (smooth-shaded, Cycles' shadow terminator Geometry Offset counts:
    measured 0.9925, 0.905 before Prism honoured it). Bump Only on the flat grid is far from both.
    ("Both": ``test_both_also_bends_the_normal_between_the_vertices_as_cycles``)."""
    _black_world(fresh_scene)
    method = "DISPLACEMENT"
    material = _displaced_material("Ridges", method, height_node="ShaderNodeTexWave", midlevel=0.5, scale=0.15)
    grid = _grid("Ground", 2.0, 96, material, smooth=smooth)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_euler = (math.radians(60.0), 0.0, math.radians(20.0))
    fresh_scene.collection.objects.link(sun)
    add_camera((0.0, -2.2, 1.6), (math.radians(55.0), 0.0, 0.0), resolution=(32, 24))
    displaced = luminance(render_prism_rgba(fresh_scene, SAMPLES))
    displaced_cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=1))
    material.displacement_method = "BUMP"
    flat_grid = luminance(render_prism_rgba(fresh_scene, SAMPLES))
    _model_the_ridges(grid, material)
    modelled = luminance(render_prism_rgba(fresh_scene, SAMPLES))
    modelled_cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=1))
    difference = np.abs(displaced - modelled).mean() / modelled.mean()
    print(f"MEASURED {method} (smooth {smooth}): displaced / modelled {displaced.mean() / modelled.mean():.4f} "
          f"(pixels {difference:.4f}); Prism / Cycles displaced {displaced.mean() / displaced_cycles.mean():.4f}, "
          f"modelled {modelled.mean() / modelled_cycles.mean():.4f}")
    assert displaced.mean() == pytest.approx(modelled.mean(), rel=0.005)
    assert difference < 0.02
    assert (displaced.mean() / displaced_cycles.mean()) == pytest.approx(modelled.mean() / modelled_cycles.mean(),
                                                                          rel=0.01)
    assert displaced.mean() / displaced_cycles.mean() == pytest.approx(1.0, abs=0.015)
    assert np.abs(flat_grid - modelled).mean() / modelled.mean() > 10 * difference


def _noise_ground(fresh_scene, subdivisions):
    """A smooth grid of ``subdivisions`` displaced by a fine Noise texture (scale 8, 5 cm) under a low sun, seen at
    a slant: its vertices sample the noise coarsely, so a bump of the same displacement adds the detail."""
    _black_world(fresh_scene)
    material = _displaced_material("Noise", "DISPLACEMENT", height_node="ShaderNodeTexNoise", midlevel=0.5,
                                   scale=0.05)
    material.node_tree.nodes["Noise Texture"].inputs["Scale"].default_value = 8.0
    _grid("Ground", 2.0, subdivisions, material, smooth=True)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_euler = (math.radians(60.0), 0.0, math.radians(20.0))
    fresh_scene.collection.objects.link(sun)
    add_camera((0.0, -2.2, 1.6), (math.radians(55.0), 0.0, 0.0), resolution=(32, 24))
    return material


def test_both_also_bends_the_normal_between_the_vertices_as_cycles(prism_addon, fresh_scene):
    """"Both" (Displacement and Bump): the vertices move, and the same displacement bends the shading normal
    between them, as Cycles' bump from displacement. On a 16 × 16 grid the bump changes Cycles' picture pixel by
    pixel; Prism's "Both" follows it: per pixel, Prism's Both is nearer Cycles' Both than Prism's Displacement
    Only is, by at least half, and the means agree within 2 %. Cycles bends that normal in object space and Prism in
    world space: the same at scale 1, and a scaled object is warned with the factor."""
    material = _noise_ground(fresh_scene, 16)
    material.displacement_method = "BOTH"
    both_cycles = luminance(render_cycles_rgba(fresh_scene, 64, max_bounces=1))
    both = luminance(render_prism_rgba(fresh_scene, 64))
    material.displacement_method = "DISPLACEMENT"
    displaced = luminance(render_prism_rgba(fresh_scene, 64))
    near = np.abs(both - both_cycles).mean() / both_cycles.mean()
    far = np.abs(displaced - both_cycles).mean() / both_cycles.mean()
    print(f"MEASURED Both: Prism / Cycles mean {both.mean() / both_cycles.mean():.4f}, per pixel |Prism Both - "
          f"Cycles Both| {near:.4f} of the mean, |Prism Displacement Only - Cycles Both| {far:.4f}")
    assert both.mean() == pytest.approx(both_cycles.mean(), rel=0.02)
    assert near < 0.5 * far
    material.displacement_method = "BOTH"
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert not [w for w in warnings if "Displacement" in w]
    bpy.data.objects["Ground"].scale = (2.0, 2.0, 2.0)
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert [w for w in warnings if "Displacement and Bump" in w] == [
        "Object 'Ground' is scaled (× 2) and its material 'Noise' uses Displacement and Bump: Cycles bends the normal in "
        "object space, Prism in world space, so Prism's bump is 0.5 × as steep as Cycles'; the displaced vertices are "
        "the same."]
