"""Particle hair (a Particle System of type Hair on a mesh) as Cycles' Blender sync reads it: the strands of the
path cache in object space with Hair Shape's radius along them, the children instead of the parents where
there are any, the settings' material slot; and a particle groom against Cycles 4.5 in absolute light and in
coverage (Render ▸ Curves ▸ Shape "3D Curves", a sun and a grey world, a transparent film)."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.hair_scenes import assert_matches_cycles, export_scene, lit
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
    assert_matches_cycles(fresh_scene, "particle groom", covered=(0.05, 0.6))


def test_ribbon_hair_carries_the_emitters_uv_map_and_colour_as_3d_curves_do(prism_addon, fresh_scene):
    """Ribbons (Render ▸ Curves ▸ Shape "Rounded Ribbons") read the emitter's UV map and colour attribute at each
    root, unwarned: they are the same round curves, each strand carrying its root's value."""
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
    _paint(plane.data, "col", lambda uv: np.column_stack([uv, np.full(len(uv), 0.5)]))
    camera((0.0, -3.0, 0.5), (0.0, 0.0, 0.2), resolution=(8, 8))
    warnings = []
    curves = export_scene(prism_addon, warnings).curves
    fresh_scene.cycles_curves.shape = "RIBBONS"
    ribbons = export_scene(prism_addon, warnings).curves
    assert warnings == []
    for table, strands in ((ribbons.uvs, curves.uvs), (ribbons.colors, curves.colors)):
        slot = next(s for s in range(len(strands)) if strands[s].any())
        assert len(np.unique(np.round(table[slot][:, 0], 5), axis=0)) == 5  # a value per strand
        np.testing.assert_array_equal(table, strands)


def _paint(mesh, name, rgb_of_uv):
    """A byte colour attribute ``name`` on the face corners of ``mesh`` whose sRGB-encoded value at each corner is
    ``rgb_of_uv(uv [L, 2])`` [L, 3] of the corner's UV (alpha 1)."""
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    mesh.uv_layers["UVMap"].uv.foreach_get("vector", uv)
    rgba = np.column_stack([rgb_of_uv(uv.reshape(-1, 2)), np.ones(len(mesh.loops))])
    mesh.attributes.new(name, "BYTE_COLOR", "CORNER").data.foreach_set("color_srgb", rgba.astype(np.float32).ravel())


def _emitter_reads(nodes, link):
    """The Vector sum of what a strand reads from its emitter: the default UV map (Texture Coordinate), the UV map
    "Shifted", and Attribute nodes reading "paint" (bytes on corners), "float_paint" and "missing"."""
    coordinates = nodes.new("ShaderNodeTexCoord")
    shifted = nodes.new("ShaderNodeUVMap")
    shifted.uv_map = "Shifted"
    total = coordinates.outputs["UV"]
    terms = [shifted.outputs["UV"]]
    for name in ("paint", "float_paint", "missing"):
        read = nodes.new("ShaderNodeAttribute")
        read.attribute_name = name
        terms.append(read.outputs["Vector"])
    for term in terms:
        add = node(nodes, "ShaderNodeVectorMath")
        link(total, add.inputs[0])
        link(term, add.inputs[1])
        total = add.outputs[0]
    return total


def test_strands_carry_the_emitters_uv_maps_and_byte_colours_at_their_roots(prism_addon, fresh_scene):
    """Each strand (parent or interpolated child) carries, along its whole length, the emitter's UV maps at its root
    (by name, and the active render one for the default: Blender's own ``Particle.uv_on_emitter`` agrees for the
    parents) and its byte corner colours there, interpolated in sRGB and decoded; a float colour attribute, which
    Cycles gives particle hair no value for, is warned as reading black; a missing one reads black unwarned."""
    lit(fresh_scene)
    plane, settings = _scalp(12, 0.3)
    mesh = plane.data
    shifted = mesh.uv_layers.new(name="Shifted")
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    mesh.uv_layers["UVMap"].uv.foreach_get("vector", uv)
    shifted.uv.foreach_set("vector", 0.5 * uv + 0.25)
    mesh.uv_layers["UVMap"].active_render = True
    _paint(mesh, "paint", lambda uv: np.column_stack([uv, np.full(len(uv), 0.25)]))
    mesh.attributes.new("float_paint", "FLOAT_COLOR", "CORNER")
    mat, nodes, link = material("Emitter reads")
    emission = node(nodes, "ShaderNodeEmission")
    link(_emitter_reads(nodes, link), emission.inputs["Color"])
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    mesh.materials.append(mat)
    camera((0.0, -3.0, 0.5), (0.0, 0.0, 0.2), resolution=(8, 8))
    warnings = []
    curves = export_scene(prism_addon, warnings).curves
    assert [w for w in warnings if "Scalp" in w] == [
        "Particle hair on 'Scalp': its material reads the emitter's attribute 'float_paint', which strands do not "
        "carry: it reads black there, as in Cycles, which gives particle hair the emitter's UV maps and its byte "
        "colour attributes on face corners (by name) at each root, nothing else."]
    evaluated = plane.evaluated_get(bpy.context.evaluated_depsgraph_get())
    system, modifier = evaluated.particle_systems[0], evaluated.modifiers["Hair"]
    segments = (1 << settings.display_step)
    roots = np.array([system.co_hair(evaluated, particle_no=n, step=0) for n in range(12)])[:, :2]
    blender_uv = np.array([system.particles[n].uv_on_emitter(modifier) for n in range(12)])
    np.testing.assert_allclose(blender_uv, roots + 0.5, atol=1e-5)
    uv_sets = [curves.uvs[s].reshape(12, segments * 2, 2) for s in range(len(curves.uvs))]
    default = next(u for u in uv_sets if np.allclose(u[:, 0], blender_uv, atol=1e-5))
    assert (default == default[:, :1]).all()  # the root's value along the whole strand
    assert any(np.allclose(u[:, 0], 0.5 * blender_uv + 0.25, atol=1e-5) for u in uv_sets)
    srgb = np.column_stack([blender_uv, np.full(12, 0.25)])
    linear = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    colours = curves.colors.reshape(len(curves.colors), 12, segments * 2, 4)[:, :, 0]
    painted = [c for c in colours if c.any()]
    assert len(painted) == 1  # float_paint and missing read black
    np.testing.assert_allclose(painted[0], np.column_stack([linear, np.ones(12)]), atol=3e-3)  # 8-bit corners

    settings.child_type, settings.child_percent = "INTERPOLATED", 3
    curves = export_scene(prism_addon).curves
    roots = curves.points[::segments + 3][:, :2]  # each strand's root (its first control point repeats it)
    uv_sets = [curves.uvs[s][::segments] for s in range(len(curves.uvs))]
    assert any(np.allclose(u[:, 0], roots + 0.5, atol=1e-5) for u in uv_sets)


def test_a_particle_groom_coloured_by_its_emitter_matches_cycles(prism_addon, fresh_scene):
    """100 hairs with two interpolated children each, grown on a 4 × 4 grid whose faces are painted a colour each
    (bytes on corners): a Diffuse colour of half (U, V, 0) from the default UV map and half the paint, both the
    emitter's at each strand's root. Prism and Cycles within 2 % in mean luminance (without them, Prism's strands
    were black)."""
    lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=4, y_subdivisions=4, size=1.0)
    grid = bpy.context.object
    grid.modifiers.new("Hair", "PARTICLE_SYSTEM")
    settings = grid.particle_systems[0].settings
    settings.type, settings.count, settings.hair_length = "HAIR", 100, 0.6
    settings.radius_scale, settings.tip_radius = 0.02, 0.2
    settings.child_type, settings.rendered_child_count, settings.roughness_1 = "INTERPOLATED", 2, 0.1
    rng = np.random.default_rng(11)
    face_colours = rng.uniform(0.1, 0.9, (len(grid.data.polygons), 3))
    _paint(grid.data, "paint", lambda uv: np.repeat(face_colours, [len(p.vertices) for p in grid.data.polygons], 0))
    mat, nodes, link = material("Root colours")
    bsdf = node(nodes, "ShaderNodeBsdfDiffuse")
    coordinates = nodes.new("ShaderNodeTexCoord")
    paint = nodes.new("ShaderNodeAttribute")
    paint.attribute_name = "paint"
    mix = node(nodes, "ShaderNodeMix", Factor=0.5)
    mix.data_type = "RGBA"
    link(coordinates.outputs["UV"], mix.inputs[6])  # the colour A and B inputs
    link(paint.outputs["Color"], mix.inputs[7])
    link(mix.outputs[2], bsdf.inputs["Color"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    grid.data.materials.append(mat)
    grid.show_instancer_for_render = False
    camera((0.0, -2.4, 1.0), (0.0, 0.0, 0.3), resolution=(48, 48))
    assert_matches_cycles(fresh_scene, "particle groom coloured by its emitter", covered=(0.05, 0.6))


def test_particle_hair_moves_with_its_emitter_under_motion_blur(prism_addon, fresh_scene):
    """An emitter keyed to move 0.4 m per frame along x, Motion Blur on (Shutter 0.5 frame, centred): its strands'
    control points at the shutter's 3 steps lie 0.1 m left of, at and right of the frame's (the emitter's mesh and
    its hair share the object's name: matched in order)."""
    from helpers.node_scenes import linear_keys

    lit(fresh_scene)
    plane, settings = _scalp(10, 0.3)
    for frame, x in ((0, -0.4), (2, 0.4)):
        plane.location.x = x
        plane.keyframe_insert("location", index=0, frame=frame)
    linear_keys(plane)
    fresh_scene.frame_set(1)
    fresh_scene.render.use_motion_blur = True
    camera((0.0, -3.0, 0.5), (0.0, 0.0, 0.2), resolution=(8, 8))
    warnings = []
    scene = export_scene(prism_addon, warnings)
    steps = scene.motion.curves
    assert steps.shape == (3, len(scene.curves.radii), 4) and not [w for w in warnings if "Scalp" in w]
    for step, shift in ((0, -0.1), (1, 0.0), (2, 0.1)):
        np.testing.assert_allclose(steps[step, :, :3], scene.curves.points + [shift, 0.0, 0.0], atol=1e-5)
