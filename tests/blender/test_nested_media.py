"""Nested media as Cycles 4.5 renders them, in absolute light (``tracer.media.nesting``): a volume inside another
volume, coloured glass inside fog, and the World's fog inside a mesh's volume all add their media where they
overlap. Both engines render the same scene in the test; mean luminance agrees within 3 %. The export warns only
where Prism still differs (a grid medium shares no space)."""

from __future__ import annotations

import importlib

import bpy
import pytest

from helpers.cycles import compare_mean_luminance
from helpers.fog_scenes import fog_world
from helpers.node_scenes import black_world, camera, material, node


def _volume_cube(name, size, location, kind="ShaderNodeVolumePrincipled", **inputs):
    mat, nodes, link = material(name)
    volume = node(nodes, kind, **inputs)
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def _lamp_behind(y=6.0, strength=2.0):
    mat, nodes, link = material("Lamp")
    emission = node(nodes, "ShaderNodeEmission", Strength=strength)
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, y, 1.0), rotation=(1.5707963, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(mat)


def _export_warnings(prism_addon):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    return warnings


def test_a_camera_inside_two_volumes_starts_in_both_as_cycles(prism_addon, fresh_scene):
    """The camera inside a haze cube inside a smoke cube, under a white world and a sun: camera rays start in
    both media, added, as in Cycles, with no warning."""
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    _volume_cube("Smoke", 4.0, (0.0, 0.0, 0.0), Color=(0.8, 0.7, 0.55), Density=0.8, Anisotropy=0.3,
                 Absorption_Color=(0.3, 0.4, 0.6))
    _volume_cube("Haze", 2.0, (0.0, 0.0, 0.0), Color=(0.5, 0.6, 0.9), Density=1.2, Anisotropy=-0.2)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    fresh_scene.collection.objects.link(sun)
    camera((0.2, -0.3, 0.1), (0.0, 4.0, 0.0), lens_mm=35.0, resolution=(24, 16))
    warnings = _export_warnings(prism_addon)
    assert not [w for w in warnings if "camera is inside" in w or "shares space" in w], warnings
    ratio = compare_mean_luminance(fresh_scene, 256, (slice(None), slice(None)), "camera inside haze in smoke")[0]
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_coloured_glass_inside_fog_matches_cycles(prism_addon, fresh_scene):
    """A marble of glass holding a Volume Absorption, inside a cube of Volume Scatter fog, before an emitter: the
    path inside the marble is in both media (absorbed by the glass's and scattered by the fog's), and leaving the
    marble it is back in the fog."""
    black_world()
    _volume_cube("Fog box", 3.0, (0.0, 0.0, 1.0), kind="ShaderNodeVolumeScatter", Color=(0.9, 0.9, 0.9), Density=0.6)
    mat, nodes, link = material("Tinted glass")
    glass = node(nodes, "ShaderNodeBsdfGlass", IOR=1.45, Roughness=0.0)
    glass.distribution = "GGX"
    absorption = node(nodes, "ShaderNodeVolumeAbsorption", Color=(0.85, 0.5, 0.3), Density=1.0)
    link(glass.outputs[0], nodes["Output"].inputs["Surface"])
    link(absorption.outputs[0], nodes["Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, location=(0.0, 0.0, 1.0), segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(mat)
    _lamp_behind()
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    assert not [w for w in _export_warnings(prism_addon) if "shares space" in w]
    ratio = compare_mean_luminance(fresh_scene, 512, (slice(8, 16), slice(8, 16)), "tinted marble in fog")[0]
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_world_fog_fills_a_volume_cube_too_as_cycles(prism_addon, fresh_scene):
    """Absorbing World fog (σ_a 0.1 per metre) and a 2 m cube of scattering Principled Volume before an emitter:
    inside the cube the fog absorbs too, as Cycles adds the World's volume to every mesh's. Without it the cube's
    light would be e^0.2 = 1.22 times brighter."""
    fog_world("ShaderNodeVolumeAbsorption", Density=0.1, Color=(0.0, 0.0, 0.0, 1.0))
    _volume_cube("Smoke", 2.0, (0.0, 0.0, 1.0), Color=(0.8, 0.8, 0.8), Density=0.5, Anisotropy=0.4)
    _lamp_behind(y=4.0)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    ratio = compare_mean_luminance(fresh_scene, 128, (slice(8, 16), slice(8, 16)), "World fog inside a smoke cube")[0]
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_a_varying_density_in_world_fog_is_warned(prism_addon, fresh_scene):
    """A density driven by a Noise Texture is a grid medium: Prism renders it alone inside its mesh, without the
    World's fog and the volume around it that Cycles adds there, and says so."""
    fog_world("ShaderNodeVolumeScatter", Density=0.05)
    _volume_cube("Room haze", 6.0, (0.0, 0.0, 0.0), kind="ShaderNodeVolumeScatter", Density=0.2)
    mat, nodes, link = material("Cloud")
    noise = node(nodes, "ShaderNodeTexNoise", Scale=3.0)
    volume = node(nodes, "ShaderNodeVolumePrincipled")
    link(noise.outputs["Fac"], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(mat)
    _lamp_behind()
    camera((0.0, -8.0, 0.0), (0.0, 0.0, 0.0), resolution=(8, 8))
    assert [w for w in _export_warnings(prism_addon) if "shares space" in w] == [
        "Material 'Cloud': its volume varies point by point (a Volume object's grid or a density driven by nodes) "
        "and shares space with material 'Room haze''s volume and the World's fog; Cycles adds them there, Prism "
        "renders 'Cloud''s volume alone inside its mesh (the others are missing there)."]
