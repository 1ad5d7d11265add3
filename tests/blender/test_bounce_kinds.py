"""Cycles' per-kind bounce limits (Light Paths ▸ Max Bounces ▸ Diffuse, Glossy, Transmission, Volume), read from
the scene where it sets them and rendered as Cycles 4.5 renders them, in absolute light. Before, Prism warned that
it had no such limits and rendered every kind up to Max Bounces: brighter than Cycles (the numbers in the tests'
prints; the closed form in tests/tracer/test_bounce_kinds.py)."""

from __future__ import annotations

import math
from importlib import import_module

import bpy
import pytest

from helpers.bpy_scenes import add_camera, add_plane
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.fog_scenes import point_light_in_fog
from helpers.node_scenes import black_world

LIMITS = dict(diffuse_bounces=1, glossy_bounces=1, transmission_bounces=2)


def _sphere(name, location, **inputs):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=location, segments=32, ring_count=16)
    obj = bpy.context.active_object
    obj.name = name
    bpy.ops.object.shade_smooth()
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    for socket, value in inputs.items():
        material.node_tree.nodes["Principled BSDF"].inputs[socket.replace("_", " ")].default_value = value
    obj.data.materials.append(material)


def _corner():
    """A white corner (floor and two walls) with a glass and a gold-coloured metal ball under an area light."""
    add_plane("Floor", 6.0, color=(0.8, 0.8, 0.8), specular=0.0)
    for name, location, rotation in (("Back", (0.0, 1.5, 3.0), (math.pi / 2, 0.0, 0.0)),
                                     ("Side", (-1.5, 0.0, 3.0), (0.0, math.pi / 2, 0.0))):
        wall = add_plane(name, 6.0, color=(0.8, 0.8, 0.8), location=location, specular=0.0)
        wall.rotation_euler = rotation
    _sphere("Glass", (0.3, 0.0, 0.5), Transmission_Weight=1.0, Roughness=0.0, IOR=1.5)
    _sphere("Metal", (-0.6, 0.6, 0.5), Base_Color=(0.9, 0.7, 0.3, 1.0), Metallic=1.0, Roughness=0.2)
    data = bpy.data.lights.new("Key", "AREA")
    data.energy, data.size = 300.0, 1.0
    key = bpy.data.objects.new("Key", data)
    key.location = (0.5, -1.0, 3.0)
    bpy.context.scene.collection.objects.link(key)
    add_camera((1.5, -4.0, 2.0), (math.radians(70), 0.0, math.radians(20)), lens_mm=35.0, resolution=(48, 36))
    bpy.context.scene.world = black_world()


def _limited_and_not(scene, samples, **limits):
    """Mean luminance at Max Bounces 8 with ``limits`` set on the scene: (Prism, Cycles), and Prism's once every
    kind is back at 8 (no limit below Max Bounces, as Prism rendered every scene before)."""
    scene.prism.max_bounces = 8
    cycles = luminance(render_cycles_rgba(scene, samples, 0, max_bounces=8, **limits)).mean()
    prism = luminance(render_prism_rgba(scene, samples, 0)).mean()
    render_cycles_rgba(scene, 1, 0, max_bounces=8)  # sets every kind to 8
    return prism, cycles, luminance(render_prism_rgba(scene, samples, 0)).mean()


def test_diffuse_glossy_and_transmission_limits_as_cycles(prism_addon, fresh_scene):
    """Max Bounces 8 with Diffuse 1, Glossy 1 and Transmission 2 (Cycles' "Fast Global Illumination" kind of
    preset): Prism within 2 % of Cycles in mean luminance, and darker than without the limits."""
    _corner()
    prism, cycles, unlimited = _limited_and_not(fresh_scene, 128, **LIMITS)
    print(f"MEASURED corner, Diffuse 1 / Glossy 1 / Transmission 2: Prism {prism:.5f}, Cycles {cycles:.5f} "
          f"(ratio {prism / cycles:.4f}); Prism without the limits {unlimited:.5f} ({unlimited / cycles:.4f})")
    assert prism == pytest.approx(cycles, rel=0.02)
    assert unlimited > 1.1 * prism


def test_volume_bounces_zero_scatters_once_in_fog_as_cycles(prism_addon, fresh_scene):
    """Volume 0 (Cycles' default, here set on the scene): light scatters once in the fog, then the path ends;
    Prism within 2 % of Cycles, and darker than with multiple scattering."""
    point_light_in_fog()
    prism, cycles, multiple = _limited_and_not(fresh_scene, 256, volume_bounces=0)
    print(f"MEASURED fog, Volume 0: Prism {prism:.5f}, Cycles {cycles:.5f} (ratio {prism / cycles:.4f}); "
          f"Prism with Volume 8 {multiple:.5f}")
    assert prism == pytest.approx(cycles, rel=0.02)
    assert multiple > 1.02 * prism


def test_only_limits_the_scene_sets_are_read(prism_addon, fresh_scene):
    """Cycles' defaults (Diffuse 4, Glossy 4, Volume 0) are not the scene's choice: never applied. Limits set are
    read, and no warning says otherwise any more."""
    settings = import_module(f"{prism_addon.__name__}.engine.export.settings")
    unrendered = import_module(f"{prism_addon.__name__}.engine.export.unrendered_settings")
    fresh_scene.prism.max_bounces = 8
    default = settings.export_settings(fresh_scene).light_path_tricks
    assert fresh_scene.cycles.diffuse_bounces == 4 and not default.limits_kinds(8)
    fresh_scene.cycles.diffuse_bounces = 2
    fresh_scene.cycles.volume_bounces = 0
    read = settings.export_settings(fresh_scene).light_path_tricks
    assert read.bounce_limits(8) == (2, 8, 8, 0)
    assert not any("Max Bounces" in m for m in unrendered.unrendered_setting_warnings(fresh_scene))


def test_the_light_paths_panel_shows_the_limits_the_scene_sets(prism_addon, fresh_scene):
    from helpers.panel_layout import context, draw, props

    panel = prism_addon.ui.panels_render.PRISM_PT_light_paths
    assert "diffuse_bounces" not in props(draw(panel, context(fresh_scene)))
    fresh_scene.cycles.diffuse_bounces = 2
    shown = props(draw(panel, context(fresh_scene)))
    assert "diffuse_bounces" in shown and "glossy_bounces" not in shown
