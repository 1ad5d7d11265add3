"""Blender's Ambient Occlusion and Bevel nodes in materials, as Cycles 4.5 renders them: rendered by Prism and
by Cycles from the same .blend and compared in absolute light, and the AO under a ceiling against its closed
form.

The AO scenes show the node through an Emission shader (strength 1): a pixel's value is the AO itself."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

SAMPLES = 32


def _ao_emission(name, colour=(1.0, 1.0, 1.0), distance=1.0, only_local=False, inside=False, samples=16):
    """A material that emits its Ambient Occlusion node's Color output (``colour`` × AO) at strength 1."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    ao = nodes.new("ShaderNodeAmbientOcclusion")
    ao.inputs["Color"].default_value = (*colour, 1.0)
    ao.inputs["Distance"].default_value = distance
    ao.only_local, ao.inside, ao.samples = only_local, inside, samples
    emission = nodes.new("ShaderNodeEmission")
    links.new(ao.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    return material


def _black_world(scene):
    scene.world = bpy.data.worlds.new("Black")
    scene.world.color = (0.0, 0.0, 0.0)
    return scene.world


def _cube(name, size, location, material):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    cube = bpy.context.active_object
    cube.name = name
    cube.data.materials.append(material)
    return cube


def _floor_under_ceiling(scene, floor_material):
    """A floor seen from straight above by a camera under a ceiling 1 m up (8 m wide: it covers every direction
    the floor's AO rays can reach within 2 m)."""
    add_plane("Floor", 4.0).data.materials[0] = floor_material
    add_plane("Ceiling", 8.0, location=(0.0, 0.0, 1.0))
    add_camera((0.0, 0.0, 0.5), (0.0, 0.0, 0.0), resolution=(16, 12))


def test_ao_under_a_ceiling_is_its_closed_form(prism_addon, fresh_scene):
    """A floor under a ceiling at height h, AO distance D: a cosine-weighted direction reaches the ceiling within
    D where cos θ > h / D, which has probability 1 - (h/D)², so AO = (h/D)² = 0.25 for h = 1, D = 2. The node's
    Distance is 0, so the World's Ambient Occlusion distance (2 m) is used, as in Cycles."""
    world = _black_world(fresh_scene)
    world.light_settings.distance = 2.0
    _floor_under_ceiling(fresh_scene, _ao_emission("AO", distance=0.0))
    prism = render_prism_rgba(fresh_scene, SAMPLES)[..., :3]
    cycles = render_cycles_rgba(fresh_scene, SAMPLES)[..., :3]
    print(f"MEASURED AO under a ceiling: Prism {prism.mean():.4f}, Cycles {cycles.mean():.4f}, closed form 0.25")
    assert prism.mean() == pytest.approx(0.25, rel=0.02)
    assert cycles.mean() == pytest.approx(0.25, rel=0.02)
    assert np.ptp(prism.reshape(-1, 3).mean(axis=0)) < 2e-3  # white × AO: grey (the spectral round trip aside)


def test_only_local_and_inside_see_no_other_object(prism_addon, fresh_scene):
    """Only Local: the ceiling is another object, so nothing occludes the floor. Inside: the rays leave through
    the floor's back, where nothing is. A Distance of 0.5 m stops short of the ceiling 1 m up. Each gives AO 1
    exactly: the image is bit for bit the one without AO rays (Distance 0 here and in the World: Cycles' early
    out), since a material's own rays draw from sample dimensions of their own. A Distance of 3 m makes the
    AO (1/3)² (the ceiling covers radius 2.8 m)."""
    world = _black_world(fresh_scene)
    world.light_settings.distance = 0.0
    material = _ao_emission("Local", distance=0.0)
    _floor_under_ceiling(fresh_scene, material)
    ao = material.node_tree.nodes["Ambient Occlusion"]
    untraced = render_prism_rgba(fresh_scene, 4)
    ao.inputs["Distance"].default_value = 3.0
    ao.only_local = True
    assert np.array_equal(render_prism_rgba(fresh_scene, 4), untraced)
    ao.only_local, ao.inside = False, True
    assert np.array_equal(render_prism_rgba(fresh_scene, 4), untraced)
    ao.inside = False
    ao.inputs["Distance"].default_value = 0.5
    assert np.array_equal(render_prism_rgba(fresh_scene, 4), untraced)
    ao.inputs["Distance"].default_value = 3.0
    far = render_prism_rgba(fresh_scene, SAMPLES)[..., :3].mean()
    print(f"MEASURED AO, distance 3 m: {far:.4f}, closed form {1 / 9:.4f}")
    assert far == pytest.approx(1.0 / 9.0, rel=0.03)


def test_ao_around_a_cube_matches_cycles(prism_addon, fresh_scene):
    """A coloured AO emission on a floor with a cube standing on it (AO darkens the floor along the cube's
    foot) and an Inside AO on the cube (its rays cross the cube and meet its far faces within 0.8 m): the
    absolute luminance of the floor near the cube and of the cube, and the image's colour, against Cycles."""
    _black_world(fresh_scene)
    add_plane("Floor", 6.0).data.materials[0] = _ao_emission("Floor AO", colour=(0.9, 0.6, 0.3))
    _cube("Cube", 1.0, (0.0, 0.0, 0.5), _ao_emission("Cube AO", distance=0.8, inside=True))
    add_camera((2.2, -2.6, 2.0), (math.radians(62.0), 0.0, math.radians(40.0)), resolution=(32, 24))
    prism = render_prism_rgba(fresh_scene, SAMPLES)[..., :3]
    cycles = render_cycles_rgba(fresh_scene, SAMPLES)[..., :3]
    p, c = luminance(prism), luminance(cycles)
    cube = np.abs(cycles[..., 0] - cycles[..., 2]) < 1e-3  # the cube is grey, the floor orange
    shaded = ~cube & (c < 0.95 * luminance(np.array([0.9, 0.6, 0.3])))  # floor the cube occludes
    print(f"MEASURED AO around a cube: image {p.mean() / c.mean():.4f}, cube {p[cube].mean() / c[cube].mean():.4f} "
          f"({cube.sum()} px), occluded floor {p[shaded].mean() / c[shaded].mean():.4f} ({shaded.sum()} px)")
    assert cube.sum() > 50 and shaded.sum() > 50
    assert p.mean() == pytest.approx(c.mean(), rel=0.02)
    assert p[cube].mean() == pytest.approx(c[cube].mean(), rel=0.03)
    assert p[shaded].mean() == pytest.approx(c[shaded].mean(), rel=0.03)
    assert prism.mean(axis=(0, 1)) == pytest.approx(cycles.mean(axis=(0, 1)), rel=0.02)


def _bevelled_cube_scene(scene, radius):
    """A flat-shaded cube whose Diffuse BSDF takes its normal from a Bevel node of ``radius``, lit by a sun from
    the side, seen across an edge and a corner."""
    _black_world(scene)
    material = bpy.data.materials.new("Bevelled")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    bevel = nodes.new("ShaderNodeBevel")
    bevel.inputs["Radius"].default_value = radius
    bevel.samples = 8
    links.new(bevel.outputs["Normal"], diffuse.inputs["Normal"])
    links.new(diffuse.outputs[0], nodes["Material Output"].inputs["Surface"])
    _cube("Cube", 1.0, (0.0, 0.0, 0.0), material)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_euler = (math.radians(50.0), math.radians(10.0), math.radians(30.0))
    scene.collection.objects.link(sun)
    add_camera((1.9, -2.3, 1.7), (math.radians(62.0), 0.0, math.radians(40.0)), lens_mm=60.0, resolution=(32, 24))
    return bevel


def test_bevel_rounds_edges_as_cycles_does(prism_addon, fresh_scene):
    """The bevelled cube against Cycles in absolute light: the whole image and the band along the edges, where
    the bevel turns the normal (pixel by pixel, Prism there is far closer to Cycles than the unbevelled cube is);
    where Cycles' faces stay flat, Prism's image is the unbevelled one."""
    bevel = _bevelled_cube_scene(fresh_scene, 0.12)
    prism = luminance(render_prism_rgba(fresh_scene, SAMPLES))
    cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=1))
    bevel.inputs["Radius"].default_value = 0.0  # the shading normal: the cube as if it had no Bevel node
    sharp = luminance(render_prism_rgba(fresh_scene, SAMPLES))
    edges = np.abs(cycles - sharp) > 0.1 * np.maximum(sharp, 0.05)
    faces = (sharp > 0.0) & (np.abs(cycles - sharp) < 0.02 * sharp)  # where Cycles' bevel leaves the face flat
    bevelled_error = np.abs(prism - cycles)[edges].mean() / cycles[edges].mean()
    sharp_error = np.abs(sharp - cycles)[edges].mean() / cycles[edges].mean()
    print(f"MEASURED bevel: image {prism.mean() / cycles.mean():.4f}, edge band {prism[edges].mean() / cycles[edges].mean():.4f} "
          f"({edges.sum()} px), mean |Prism - Cycles| there {bevelled_error:.4f} of Cycles (unbevelled: "
          f"{sharp_error:.4f}), faces {faces.sum()} px")
    assert edges.sum() > 20 and faces.sum() > 50
    assert prism.mean() == pytest.approx(cycles.mean(), rel=0.02)
    assert prism[edges].mean() == pytest.approx(cycles[edges].mean(), rel=0.04)
    assert bevelled_error < 0.3 * sharp_error  # pixel by pixel, the edges are Cycles' rounded ones
    flat = faces & (np.abs(prism - sharp) < 0.02 * sharp)
    print(f"MEASURED bevel: {flat.sum()} of the {faces.sum()} px Cycles leaves flat within 2 % are so in Prism")
    assert flat.sum() >= 0.9 * faces.sum()
