"""Particle hair (a Particle System of type Hair on a mesh) as Cycles' Blender sync reads it: the strands of the
path cache in object space with Hair Shape's radius along them, the children instead of the parents where
there are any, the settings' material slot; and a particle groom against Cycles 4.5 in absolute light and in
coverage (Render ▸ Curves ▸ Shape "3D Curves", a sun and a grey world, a transparent film)."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.hair_scenes import export_scene, lit, luminance_and_coverage
from helpers.node_scenes import camera, material, node


def _diffuse(name, colour):
    mat, nodes, link = material(name)
    link(node(nodes, "ShaderNodeBsdfDiffuse", Color=colour).outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _scalp(count, length, size=1.0, location=(0.0, 0.0, 0.0)):
    """A plane growing ``count`` hairs of ``length`` m straight up (the settings returned)."""
    bpy.ops.mesh.primitive_plane_add(size=size, location=location)
    plane = bpy.context.object
    plane.name = "Scalp"
    plane.modifiers.new("Hair", "PARTICLE_SYSTEM")
    settings = plane.particle_systems[0].settings
    settings.type, settings.count, settings.hair_length = "HAIR", count, length
    return plane, settings


def test_particle_strands_export_from_the_path_cache_with_hair_shape(prism_addon, fresh_scene):
    lit(fresh_scene)
    plane, settings = _scalp(10, 0.3, location=(1.0, 2.0, 0.5))
    plane.scale = (2.0, 2.0, 2.0)
    settings.radius_scale, settings.root_radius, settings.tip_radius = 0.02, 1.0, 0.5
    settings.shape, settings.use_close_tip = 0.0, False
    plane.data.materials.append(_diffuse("Skin", (0.8, 0.6, 0.5)))
    plane.data.materials.append(_diffuse("Fur", (0.3, 0.2, 0.1)))
    settings.material = 2
    camera((1.0, -4.0, 1.0), (1.0, 2.0, 0.6), resolution=(8, 8))
    warnings = []
    scene = export_scene(prism_addon, warnings)
    curves = scene.curves
    evaluated = plane.evaluated_get(bpy.context.evaluated_depsgraph_get())
    system = evaluated.particle_systems[0]
    steps = (1 << settings.display_step) + 1  # a viewport evaluation: Viewport Display Steps
    assert len(curves) == 10 * (steps - 1) and not any("particle" in w for w in warnings)
    root = np.array(system.co_hair(evaluated, particle_no=0, step=0))
    tip = np.array(system.co_hair(evaluated, particle_no=0, step=steps - 1))
    # each strand's ends repeated once (Catmull-Rom control points): strand 0 spans points 0 .. steps + 1
    np.testing.assert_allclose(curves.points[0], root, atol=1e-5)
    np.testing.assert_allclose(curves.points[steps + 1], tip, atol=1e-5)
    # the radius goes linearly (Strand Shape 0) from Radius Scale / 2 × Root to × Tip, times the object's scale
    np.testing.assert_allclose(curves.radii[0], 2.0 * 0.01 * 1.0, rtol=1e-5)
    np.testing.assert_allclose(curves.radii[steps + 1], 2.0 * 0.01 * 0.5, rtol=1e-5)
    assert {scene.materials[m].name for m in curves.material} == {"Fur"}

    settings.child_type, settings.child_percent = "INTERPOLATED", 3  # children replace the parents
    settings.use_close_tip = True
    scene = export_scene(prism_addon)
    assert len(scene.curves) == 10 * 3 * (steps - 1)
    assert scene.curves.radii.min() == 0.0  # Close Tip

    plane.modifiers["Hair"].show_viewport = False  # the modifier off for this evaluation: no strands
    assert export_scene(prism_addon).curves is None


def test_a_particle_groom_matches_cycles_in_luminance_and_coverage(prism_addon, fresh_scene):
    """100 hairs with two interpolated, roughened children each (the children render, not the parents), 1 cm
    thick at the root tapering to 2 mm (Radius Scale 0.02, Tip 0.2): mean luminance and mean alpha of Prism and
    Cycles within 2 %. F12 renders evaluate the system for render (Render Steps, Render Amount), as Cycles."""
    lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    plane, settings = _scalp(100, 0.6)
    settings.radius_scale, settings.tip_radius = 0.02, 0.2
    settings.child_type, settings.rendered_child_count, settings.roughness_1 = "INTERPOLATED", 2, 0.1
    plane.data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    plane.show_instancer_for_render = False  # the strands alone: Render ▸ Show Emitter off
    camera((0.0, -2.4, 1.0), (0.0, 0.0, 0.3), resolution=(48, 48))
    light, coverage, covered = luminance_and_coverage(fresh_scene, "particle groom")
    assert 0.05 < covered < 0.6  # the strands cover part of the picture
    assert light == pytest.approx(1.0, abs=0.02)
    assert coverage == pytest.approx(1.0, abs=0.02)


def test_hair_reading_a_uv_map_or_attribute_is_warned(prism_addon, fresh_scene):
    """Strands carry no UV maps or attributes in Prism (Cycles gives particle hair the emitter's UV at the root):
    a hair material reading them is named, with what it reads and what renders instead."""
    lit(fresh_scene)
    plane, settings = _scalp(5, 0.3)
    mat, nodes, link = material("Textured fur")
    shader = node(nodes, "ShaderNodeBsdfDiffuse")
    mix = node(nodes, "ShaderNodeVectorMath")  # Add
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = "UVMap"
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "col"
    link(uv.outputs["UV"], mix.inputs[0])
    link(attribute.outputs["Vector"], mix.inputs[1])
    link(mix.outputs[0], shader.inputs["Color"])
    link(shader.outputs[0], nodes["Output"].inputs["Surface"])
    plane.data.materials.append(mat)
    camera((0.0, -3.0, 0.5), (0.0, 0.0, 0.2), resolution=(8, 8))
    warnings = []
    export_scene(prism_addon, warnings)
    assert [w for w in warnings if w.startswith("Hair 'Scalp'")] == [
        "Hair 'Scalp': its material reads the UV map 'UVMap', the attribute 'col', but Prism's strands carry no UV "
        "maps or attributes: it reads 0 there (UV (0, 0), attributes black), where Cycles reads the strands' own (for "
        "particle hair, the emitter's at each root)."]
