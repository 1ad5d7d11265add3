"""Homogeneous media against Cycles, in absolute light: a Principled Volume cube (scattering, absorption,
anisotropy) lit by a white world and a sun, an emitting Principled Volume cube in the dark, and a Glass BSDF cube holding a Volume Absorption (coloured,
still refracting glass) in front of an emitter. Both scenes are rendered by both engines in the test; the
mean luminance of the pixels that see the cube agrees within 3 %. The export keeps every setting (no
warning)."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.cycles import compare_mean_luminance
from helpers.node_scenes import black_world, camera, material, node


def _cube(name, mat, size=2.0, location=(0.0, 0.0, 1.0)):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def _white_world(strength):
    world = black_world()
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = strength
    return world


def _principled_volume():
    mat, nodes, link = material("Smoke")
    volume = node(nodes, "ShaderNodeVolumePrincipled", Color=(0.8, 0.7, 0.55), Density=0.8, Anisotropy=0.3,
                  Absorption_Color=(0.3, 0.4, 0.6))
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _tinted_glass():
    mat, nodes, link = material("Tinted glass")
    glass = node(nodes, "ShaderNodeBsdfGlass", IOR=1.45, Roughness=0.0)
    glass.distribution = "GGX"  # roughness 0: a smooth dielectric in both engines
    absorption = node(nodes, "ShaderNodeVolumeAbsorption", Color=(0.85, 0.6, 0.35), Density=0.5)
    link(glass.outputs[0], nodes["Output"].inputs["Surface"])
    link(absorption.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _compare(scene, samples, region, what):
    return compare_mean_luminance(scene, samples, region, what)[0]


def test_principled_volume_cube_matches_cycles(prism_addon, fresh_scene):
    _white_world(1.0)
    _cube("Smoke", _principled_volume())
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    fresh_scene.collection.objects.link(sun)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    ratio = _compare(fresh_scene, 256, (slice(6, 18), slice(6, 18)), "Principled Volume cube")
    assert ratio == pytest.approx(1.0, abs=0.03)


def _glowing_cube_ratio(fresh_scene, name, label, **volume_inputs) -> float:
    """Prism / Cycles of a cube filled with a Principled Volume of ``volume_inputs`` in a black world, seen
    face on (128 spp, the cube's middle 12 × 12 pixels)."""
    black_world()
    mat, nodes, link = material(name)
    volume = node(nodes, "ShaderNodeVolumePrincipled", **volume_inputs)
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    _cube(name, mat)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    return _compare(fresh_scene, 128, (slice(6, 18), slice(6, 18)), label)


def test_emitting_principled_volume_matches_cycles(prism_addon, fresh_scene):
    """Emission Strength × Emission Color is radiance per metre, not scaled by density, in a scattering and
    absorbing medium, in a black world: all the light is the medium's own."""
    ratio = _glowing_cube_ratio(fresh_scene, "Glow", "emitting Principled Volume cube", Color=(0.6, 0.6, 0.6),
                                Density=1.5, Emission_Strength=0.4, Emission_Color=(1.0, 0.6, 0.3))
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_glass_with_absorbing_interior_matches_cycles(prism_addon, fresh_scene):
    black_world()
    _cube("Gem", _tinted_glass())
    lamp_mat, nodes, link = material("Lamp")
    emission = node(nodes, "ShaderNodeEmission", Strength=2.0)
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0.0, 6.0, 1.0), rotation=(1.5707963, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(lamp_mat)
    camera((0.0, -8.0, 1.0), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(24, 24))
    ratio = _compare(fresh_scene, 64, (slice(8, 16), slice(8, 16)), "Glass + Volume Absorption cube")
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_volume_settings_export_as_a_medium(prism_addon, fresh_scene):
    """(A Density driven by nodes: ``test_textured_volume.py``.)"""
    nodes_module = importlib.import_module(f"{prism_addon.__name__}.engine.export.nodes")
    compiled = nodes_module.compile_material(_principled_volume(), load_pixels=False)
    assert compiled.warnings == []
    medium = compiled.medium
    (density, colour), = medium.scatter
    assert density == pytest.approx(0.8) and colour == pytest.approx((0.8, 0.7, 0.55))
    assert medium.anisotropy == pytest.approx(0.3)
    assert not medium.density_varies


def test_blackbody_principled_volume_matches_cycles(prism_addon, fresh_scene):
    """Blackbody Intensity 1 at 1800 K: σ_SB T⁴ × 10⁻⁶ / π of luminance-1 blackbody light per metre (Cycles'
    Stefan-Boltzmann scaling), in an absorbing, scattering medium in the dark."""
    ratio = _glowing_cube_ratio(fresh_scene, "Flame", "blackbody Principled Volume cube", Color=(0.5, 0.5, 0.5),
                                Density=1.0, Blackbody_Intensity=1.0, Temperature=1800.0)
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_a_camera_inside_a_volume_starts_in_it_as_cycles(prism_addon, fresh_scene):
    """The camera inside a smoke cube (Principled Volume) under a white world and a sun: camera rays start in
    the smoke, as in Cycles (absolute mean luminance within 3 %), with no warning."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    _white_world(1.0)
    _cube("Smoke", _principled_volume(), size=4.0, location=(0.0, 0.0, 0.0))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, -5.0))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    fresh_scene.collection.objects.link(sun)
    camera((0.5, -0.3, 0.2), (0.0, 4.0, 0.0), lens_mm=35.0, resolution=(24, 16))
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert not [w for w in warnings if "camera is inside" in w], warnings
    ratio = _compare(fresh_scene, 256, (slice(None), slice(None)), "camera inside a smoke cube")
    assert ratio == pytest.approx(1.0, abs=0.03)
