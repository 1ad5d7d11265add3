"""Hair Curves as round curves (Render ▸ Curves ▸ Shape "3D Curves"): strands exported as
Catmull-Rom segments in world space with the radius attribute scaled as Cycles scales it and the material
slot of each curve; "Rounded Ribbons" keeps Prism's camera-facing ribbons; a groom of a few hundred
curved, tapering strands with a Diffuse BSDF under a sun and a grey world against Cycles 4.5, in absolute
mean luminance and in coverage (alpha over a transparent film); a moving groom warned under motion blur."""

from __future__ import annotations

import numpy as np
import pytest

from helpers.hair_scenes import export_scene as _export, groom as _groom, hair_object as _hair_object, lit as _lit
from helpers.hair_scenes import luminance_and_coverage
from helpers.node_scenes import camera, material, node


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

    fresh_scene.cycles_curves.shape = "RIBBONS"  # Rounded Ribbons: Prism's camera-facing ribbons
    scene = _export(prism_addon)
    assert scene.curves is None and scene.triangle_count == 2 * (3 + 2)


def test_a_groom_matches_cycles_in_luminance_and_coverage(prism_addon, fresh_scene):
    """300 curved, tapering strands (Diffuse BSDF) over a transparent film: mean luminance and mean alpha of
    Prism and Cycles within 2 %."""
    _lit(fresh_scene)
    fresh_scene.render.film_transparent = True
    sizes, positions, radii = _groom()
    _hair_object("Groom", sizes, positions, radii=radii).data.materials.append(_diffuse("Hair", (0.7, 0.5, 0.3)))
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(48, 48))
    light, coverage, covered = luminance_and_coverage(fresh_scene, "groom")
    assert 0.1 < covered < 0.6  # the strands cover part of the picture
    assert light == pytest.approx(1.0, abs=0.02)
    assert coverage == pytest.approx(1.0, abs=0.02)


def test_a_moving_groom_is_warned_under_motion_blur(prism_addon, fresh_scene):
    _lit(fresh_scene)
    sizes, positions, radii = _groom(count=20)
    obj = _hair_object("Groom", sizes, positions, radii=radii)
    for frame, x in ((0, -0.2), (2, 0.2)):
        obj.location.x = x
        obj.keyframe_insert("location", index=0, frame=frame)
    fresh_scene.frame_set(1)
    fresh_scene.render.use_motion_blur = True
    camera((0.0, -2.6, 1.2), (0.0, 0.0, 0.45), resolution=(16, 16))
    warnings = []
    scene = _export(prism_addon, warnings)
    assert len(scene.curves) == 20 * 5
    assert ("Hair curves 'Groom' move during the shutter, but Prism renders 3D curves without motion blur: the "
            "strands are sharp where they stand at the frame.") in warnings
