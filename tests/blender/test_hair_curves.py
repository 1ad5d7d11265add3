"""Hair Curves as round curves (Render ▸ Curves ▸ Shape "3D Curves", and "Rounded Ribbons" too): strands exported
as Catmull-Rom segments in world space with the radius attribute scaled as Cycles scales it and the material
slot of each curve; a groom of a few hundred curved, tapering strands with a Diffuse BSDF under a sun and a grey
world against Cycles 4.5, in absolute mean luminance and in coverage (alpha over a transparent film), also
coloured by its curve and point attributes, and as Rounded Ribbons from three sides and glowing with its Hair
Info; a moving groom blurred as Cycles blurs it, and a still one by its velocity attribute."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.hair_scenes import export_scene as _export, groom as _groom, hair_object as _hair_object, lit as _lit
from helpers.hair_scenes import assert_matches_cycles, tint_and_fade
from helpers.node_scenes import camera, material, node, slide_during_shutter


def _diffuse(name, colour):
    mat, nodes, link = material(name)
    bsdf = node(nodes, "ShaderNodeBsdfDiffuse", Color=colour)
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def test_strands_export_as_world_curve_segments(prism_addon, fresh_scene):
    _lit(fresh_scene)
    positions = [(0, 0, 0), (0, 0, 0.5), (0.1, 0, 1.0), (0.2, 0, 1.5), (1, 0, 0), (1, 0, 0.5), (1, 0.2, 1.0)]
    obj = _hair_object("Fur", [4, 3], positions, radii=np.full(7, 0.02), curve_slots=[1, 0])
    for colour in ((0.8, 0.2, 0.2), (0.2, 0.8, 0.2)):
        obj.data.materials.append(_diffuse(f"Fur {colour}", colour))
    obj.location = (0.0, 2.0, 0.0)
    obj.scale = (2.0, 2.0, 2.0)
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 0.5), resolution=(16, 16))
    scene = _export(prism_addon)
    curves = scene.curves
    assert scene.triangle_count == 0 and len(curves) == 3 + 2
    world = np.array(positions) * 2.0 + (0.0, 2.0, 0.0)
    # each strand's ends repeated once: the 4 control points of Embree's and Cycles' Catmull-Rom segments
    np.testing.assert_allclose(curves.points, world[[0, 0, 1, 2, 3, 3, 4, 4, 5, 6, 6]], atol=1e-6)
    np.testing.assert_array_equal(curves.segments, [0, 1, 2, 6, 7])
    np.testing.assert_allclose(curves.radii, 0.04, rtol=1e-6)  # scaled by the object's scale, as Cycles
    names = [scene.materials[m].name for m in curves.material]
    assert names[:3] == ["Fur (0.2, 0.8, 0.2)"] * 3 and names[3:] == ["Fur (0.8, 0.2, 0.2)"] * 2
    assert {scene.object_names[o] for o in curves.object} == {"Fur"}

    fresh_scene.cycles_curves.shape = "RIBBONS"  # Rounded Ribbons, a new scene's shape: the same round curves
    ribbons = _export(prism_addon)
    assert ribbons.triangle_count == 0
    np.testing.assert_array_equal(ribbons.curves.points, curves.points)
    np.testing.assert_array_equal(ribbons.curves.radii, curves.radii)


def test_a_groom_matches_cycles_in_luminance_and_coverage(prism_addon, fresh_scene):
    """300 curved, tapering strands (Diffuse BSDF) over a transparent film: mean luminance and mean alpha of
    Prism and Cycles within 2 %."""
    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    _hair_object("Groom", sizes, positions, radii=radii).data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    assert_matches_cycles(fresh_scene, "groom")


def _moving_groom(scene, count=300):
    """A groom keyed to move 0.8 m along x over two frames at constant speed (x = 0 at frame 1), Motion Blur on
    (Shutter 0.5 frame, centred on frame 1: 0.2 m of travel while it is open)."""
    sizes, positions, radii = _groom(count=count)
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    slide_during_shutter(obj, scene)
    return obj


def test_a_moving_groom_exports_its_points_at_the_shutters_steps(prism_addon, fresh_scene):
    """The strands' control points at the shutter's 3 time steps (open, middle, close: 0.1 m left of the frame's,
    the frame's, 0.1 m right), unwarned; with the object's Motion Blur off it is still, as in Cycles."""
    _lit(fresh_scene)
    obj = _moving_groom(fresh_scene, count=20)
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(16, 16))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert not [w for w in warnings if "Groom" in w]
    steps = scene.motion.curves
    assert steps.shape == (3, len(scene.curves.radii), 4) and scene.motion.vertices is None
    np.testing.assert_allclose(steps[1, :, :3], scene.curves.points, atol=1e-6)
    for step, shift in ((0, -0.1), (2, 0.1)):
        np.testing.assert_allclose(steps[step, :, :3], scene.curves.points + [shift, 0.0, 0.0], atol=1e-5)
    np.testing.assert_array_equal(steps[:, :, 3], np.broadcast_to(scene.curves.radii, steps.shape[:2]))
    obj.cycles.use_motion_blur = False
    assert _export(prism_addon).motion is None


def test_hair_whose_strands_change_during_the_shutter_stays_still_warned(prism_addon):
    """Per object (matched by name): a groom whose point count changes at a time step renders still and is named;
    another that keeps its points moves; one whose Motion Blur is off stays still unwarned."""
    import importlib

    hair_steps = importlib.import_module(f"{prism_addon.__name__}.engine.export.hair_motion").hair_steps
    curves_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.curves")

    def strands(shift, counts):  # one 4-point strand per object, object k moved by shift[k] along x
        points, radii, segments, objects, first = [], [], [], [], 0
        for k, count in enumerate(counts):
            for _ in range(count):
                line = np.linspace([0.0, k, 0.0], [0.0, k, 1.0], 4) + [shift[k], 0.0, 0.0]
                p, r, seg = curves_module.padded_strands(line, np.full(4, 0.01), np.array([0, 4]))
                points.append(p)
                radii.append(r)
                segments.append(seg + first)
                objects.append(np.full(len(seg), k, np.int32))
                first += len(p)
        segments = np.concatenate(segments)
        return curves_module.CurveSegments(np.concatenate(points), np.concatenate(radii), segments,
                                           np.zeros(len(segments), np.int32), np.concatenate(objects))

    names = ["Changing", "Moving", "Blur off"]
    frame = strands([0.0, 0.0, 0.0], [1, 1, 1])
    scene = type("S", (), dict(curves=frame, object_names=names))
    steps = [(strands([-0.1, -0.1, -0.1], [2, 1, 1]), names), (frame, names),
             (strands([0.1, 0.1, 0.1], [1, 1, 1]), list(reversed(names)))]  # names in another order
    settings = {"Changing": (True, 1, True), "Moving": (True, 1, True), "Blur off": (False, 1, True)}
    warnings = []
    table = hair_steps(scene, steps, settings, 3, warnings)
    owner = np.repeat([0, 1, 2], 6)  # 6 padded control points per strand
    assert table.shape == (3, 18, 4)
    np.testing.assert_array_equal(table[:, owner != 1], np.broadcast_to(table[1, owner != 1], (3, 12, 4)))
    np.testing.assert_allclose(table[0, owner == 1, 0], -0.1)
    assert len(warnings) == 1 and warnings[0].startswith("Hair 'Changing': its strands change their number of points")


def test_a_moving_groom_is_blurred_as_cycles_blurs_it(prism_addon, fresh_scene):
    """300 strands moving 0.2 m sideways while the shutter is open (a few pixels of this 48 px view, several
    times their spacing): Prism's blurred groom matches Cycles' within 2 % in mean luminance, coverage and how
    the smear spreads the coverage (mean alpha² over mean alpha: measured 1.0008), which the sharp groom misses
    by more than twice that (measured 1.0635)."""
    from helpers.blur_compare import blur_ratios

    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    obj = _moving_groom(fresh_scene)
    obj.data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    ratios = blur_ratios(fresh_scene, 64, "moving groom under motion blur")
    assert ratios.light == pytest.approx(1.0, abs=0.02)
    assert ratios.coverage == pytest.approx(1.0, abs=0.02)
    assert ratios.squared == pytest.approx(1.0, abs=0.02)
    assert ratios.spread == pytest.approx(1.0, abs=0.02)
    assert abs(ratios.sharp_spread - 1.0) > 0.04


def test_a_groom_with_a_velocity_attribute_blurs_by_it_as_cycles(prism_addon, fresh_scene):
    """A still groom whose points carry a ``velocity`` attribute of 12 m/s along x (what a simulation or cache
    writes): Cycles takes the attribute over the steps, so Prism does: control points ±0.125 m at the shutter's
    ends (Shutter 0.5 frame at 24 fps), radii the frame's, unwarned; rendered within 2 % of Cycles in mean
    luminance, coverage and spread, where the sharp groom misses the spread."""
    from helpers.blur_compare import blur_ratios

    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    fresh_scene.render.use_motion_blur, fresh_scene.render.motion_blur_shutter = True, 0.5
    sizes, positions, radii = _groom()
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    velocity = obj.data.attributes.new("velocity", "FLOAT_VECTOR", "POINT")
    velocity.data.foreach_set("vector", np.tile([12.0, 0.0, 0.0], len(positions)).astype(np.float32))
    obj.data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    steps = scene.motion.curves
    for step, shift in ((0, -0.125), (1, 0.0), (2, 0.125)):
        np.testing.assert_allclose(steps[step, :, :3], scene.curves.points + [shift, 0.0, 0.0], atol=1e-5)
    np.testing.assert_array_equal(steps[:, :, 3], np.broadcast_to(scene.curves.radii, steps.shape[:2]))
    ratios = blur_ratios(fresh_scene, 64, "a still groom moved by its velocity attribute")
    assert ratios.light == pytest.approx(1.0, abs=0.02)
    assert ratios.coverage == pytest.approx(1.0, abs=0.02)
    assert ratios.spread == pytest.approx(1.0, abs=0.02)
    assert abs(ratios.sharp_spread - 1.0) > 0.04


def _attribute_emission(name, attributes):
    """An Emission whose Color is the sum of the Attribute nodes reading ``attributes`` (their Vector outputs)."""
    mat, nodes, link = material(name)
    emission = node(nodes, "ShaderNodeEmission")
    total = None
    for attribute_name in attributes:
        read = nodes.new("ShaderNodeAttribute")
        read.attribute_name = attribute_name
        if total is None:
            total = read.outputs["Vector"]
            continue
        add = node(nodes, "ShaderNodeVectorMath")
        link(total, add.inputs[0])
        link(read.outputs["Vector"], add.inputs[1])
        total = add.outputs[0]
    link(total, emission.inputs["Color"])
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def test_strand_attributes_export_at_each_segments_ends(prism_addon, fresh_scene):
    """A curve-domain colour and a point-domain float, read by Attribute nodes, reach the tracer as each segment's
    RGBA at its two points (a curve's value at both; a point's interpolated along the segment by the kernels);
    an attribute the strands lack reads black, unwarned, as in Cycles. Rounded Ribbons carry the same values, being
    the same curves."""
    _lit(fresh_scene)
    positions = [(0, 0, 0), (0, 0, 0.5), (0.1, 0, 1.0), (0.2, 0, 1.5), (1, 0, 0), (1, 0, 0.5), (1, 0.2, 1.0)]
    obj = _hair_object("Fur", [4, 3], positions, radii=np.full(7, 0.02))
    tint = obj.data.attributes.new("tint", "FLOAT_COLOR", "CURVE")
    tint.data.foreach_set("color", [1.0, 0.5, 0.0, 1.0, 0.0, 0.25, 1.0, 0.5])
    obj.data.attributes.new("w", "FLOAT", "POINT").data.foreach_set("value", np.arange(7.0) / 10.0)
    obj.data.materials.append(_attribute_emission("Attributes", ["tint", "w", "missing"]))
    camera((0.0, -6.0, 1.0), (0.0, 0.0, 0.5), resolution=(16, 16))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    colors = scene.curves.colors
    assert colors.shape == (3, 5, 2, 4)
    slots = [s for s in range(3) if colors[s].any()]
    assert len(slots) == 2  # "missing" reads black, alpha 0 (as in Cycles)
    tint_slot = next(s for s in slots if colors[s, 0, 0, 1] == 0.5)
    w_slot = next(s for s in slots if s != tint_slot)
    np.testing.assert_allclose(colors[tint_slot, :3], [[[1.0, 0.5, 0.0, 1.0]] * 2] * 3)
    np.testing.assert_allclose(colors[tint_slot, 3:], [[[0.0, 0.25, 1.0, 0.5]] * 2] * 2)
    ends = np.array([[0, 1], [1, 2], [2, 3], [4, 5], [5, 6]]) / 10.0
    np.testing.assert_allclose(colors[w_slot, :, :, 0], ends, atol=1e-7)
    np.testing.assert_allclose(colors[w_slot, :, :, :3], np.repeat(ends[..., None], 3, axis=-1), atol=1e-7)

    fresh_scene.cycles_curves.shape = "RIBBONS"
    ribbons = _export(prism_addon, warnings)
    assert warnings == [] and ribbons.triangle_count == 0
    np.testing.assert_array_equal(ribbons.curves.colors, colors)  # the same strands, the same values


def test_a_groom_coloured_by_its_attributes_matches_cycles(prism_addon, fresh_scene):
    """300 strands whose Diffuse colour is a random colour per strand (curve domain) times a brightness rising
    from root to tip (point domain, interpolated along each segment): Prism and Cycles within 2 % in mean
    luminance and coverage (without the attributes Prism's strands were black)."""
    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    obj.data.materials.append(tint_and_fade(obj, sizes, np.random.default_rng(5)))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    assert_matches_cycles(fresh_scene, "groom coloured by attributes")


def test_ribbons_coloured_by_their_attributes_glow_as_in_cycles(prism_addon, fresh_scene):
    """The same groom as "Rounded Ribbons" (a new scene's shape) whose Emission colour is its curve and point
    attributes, in the dark: Prism's ribbons (round curves) and Cycles' agree within 2 % in mean luminance and
    coverage."""
    from helpers.node_scenes import black_world

    black_world()
    fresh_scene.cycles_curves.shape = "RIBBONS"
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    tint_and_fade(obj, sizes, np.random.default_rng(5))
    obj.data.materials.append(_attribute_emission("Glowing attributes", ["tint", "fade"]))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    assert_matches_cycles(fresh_scene, "ribbons glowing with their attributes")


@pytest.mark.parametrize("view", ["front", "side", "back"])
def test_a_sunlit_groom_as_rounded_ribbons_matches_cycles_ribbons(prism_addon, fresh_scene, view):
    """The Diffuse groom as "Rounded Ribbons", seen from the sun's side, across it and against it: Cycles' ribbons
    face every ray with a rounded normal, and Prism's round curves show each ray the same width and normals, so the
    two agree within 2 % in mean luminance and coverage (Prism's former camera-facing triangles were 13 % and 19 %
    brighter seen from the front and the side: to the sun they were edge-on strips)."""
    _lit(fresh_scene)
    fresh_scene.cycles_curves.shape = "RIBBONS"
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    _hair_object("Groom", sizes, positions, radii=radii).data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    eye = {"front": (0.0, -2.6, 1.2), "side": (2.4, -1.0, 1.0), "back": (0.0, 2.6, 0.6)}[view]
    camera(eye, (0.0, 0.0, 0.45), resolution=(48, 48))
    assert_matches_cycles(fresh_scene, f"sunlit groom as Rounded Ribbons, {view}")


def test_rounded_ribbons_read_hair_info_as_cycles_ribbons(prism_addon, fresh_scene):
    """Ribbons glowing with Hair Info ▸ Intercept (red) and Random (green), unwarned: within 2 % of Cycles' ribbons
    in mean luminance and coverage (Prism's former triangle ribbons read 0 there, warned)."""
    from helpers.node_scenes import black_world

    black_world()
    fresh_scene.cycles_curves.shape = "RIBBONS"
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    mat, nodes, link = material("Hair Info glow")
    emission, combine, info = node(nodes, "ShaderNodeEmission"), nodes.new("ShaderNodeCombineXYZ"), nodes.new(
        "ShaderNodeHairInfo")
    link(info.outputs["Intercept"], combine.inputs["X"])
    link(info.outputs["Random"], combine.inputs["Y"])
    link(combine.outputs[0], emission.inputs["Color"])
    link(emission.outputs[0], nodes["Output"].inputs["Surface"])
    obj.data.materials.append(mat)
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    warnings = []
    _export(prism_addon, warnings)
    assert warnings == []
    assert_matches_cycles(fresh_scene, "ribbons glowing with their Hair Info")


def test_a_groom_coloured_through_its_surface_uv_matches_cycles(prism_addon, fresh_scene):
    """300 strands with the curve-domain 2D vector "surface_uv_coordinate" (where Blender records the root of hair
    grown on a surface) and a Diffuse colour (U, V, 0.3) from Texture Coordinate ▸ UV: Cycles takes the first such
    attribute as the strands' UV map, and Prism within 2 % of it in mean luminance (without it, Prism read
    UV (0, 0) and warned)."""
    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    uv = np.random.default_rng(7).uniform(0.1, 0.9, (len(sizes), 2))
    obj.data.attributes.new("surface_uv_coordinate", "FLOAT2", "CURVE").data.foreach_set("vector", uv.ravel())
    mat, nodes, link = material("UV hair")
    bsdf = node(nodes, "ShaderNodeBsdfDiffuse")
    coordinates = nodes.new("ShaderNodeTexCoord")
    add = node(nodes, "ShaderNodeVectorMath")
    add.inputs[1].default_value = (0.0, 0.0, 0.3)
    link(coordinates.outputs["UV"], add.inputs[0])
    link(add.outputs[0], bsdf.inputs["Color"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    obj.data.materials.append(mat)
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert warnings == []
    np.testing.assert_allclose(scene.curves.uvs[0, :5], np.tile(uv[0], (5, 2, 1)), atol=1e-7)  # strand 0's segments
    assert_matches_cycles(fresh_scene, "groom coloured by its surface UV", covered=None)
