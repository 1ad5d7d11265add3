"""Object ▸ Shading ▸ Shadow Terminator ▸ Geometry Offset, as Cycles 4.5 renders it: a coarse smooth-shaded sphere
under a low sun, Prism against Cycles in absolute light from the same scene, at the default offset (0.1), at 0 and
at 1; and its Shading Offset, on a mesh (on hair and point clouds it is warned).

Measured: Prism / Cycles 0.9994 at 0.1 and at 1, 0.9991 at 0. Before (48224aa, this scene), Prism ignored the
offset: 0.9637 at 0.1 and at 1 (the facets' shadow along the terminator, which Cycles lifts the shadow rays
over), 0.9991 at 0.
"""

from __future__ import annotations

import importlib

import bpy
import pytest

from helpers.bpy_scenes import coarse_sphere_under_low_sun
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

SAMPLES = 16


def _coarse_sphere_under_low_sun():
    """``coarse_sphere_under_low_sun`` at 32 × 32, Max Bounces 0: direct light only."""
    sphere = coarse_sphere_under_low_sun()
    bpy.context.scene.prism.max_bounces = 0
    return sphere


@pytest.mark.parametrize("offset", [0.1, 0.0, 1.0])
def test_the_geometry_offset_renders_as_in_cycles(prism_addon, fresh_scene, offset):
    """Prism / Cycles mean luminance within 1.5 % at each offset (16 spp, 32 × 32: the noise of the ratio is
    about 0.3 %); the offsets change Cycles' image by several percent, so each is honoured, not averaged over."""
    sphere = _coarse_sphere_under_low_sun()
    sphere.shadow_terminator_geometry_offset = offset
    prism = luminance(render_prism_rgba(fresh_scene, SAMPLES)).mean()
    cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=0)).mean()
    print(f"MEASURED Geometry Offset {offset}: Prism {prism:.5f}, Cycles {cycles:.5f}, ratio {prism / cycles:.4f}")
    assert prism / cycles == pytest.approx(1.0, abs=0.015)


@pytest.mark.parametrize("shading_offset", [0.3, 0.8])
def test_the_shading_offset_renders_as_in_cycles(prism_addon, fresh_scene, shading_offset):
    """The Shading Offset darkens the sphere toward its terminator in both engines alike: Prism / Cycles within
    1.5 %, where the offset changes Cycles' image by far more (measured below); and no warning for a mesh."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    sphere = _coarse_sphere_under_low_sun()
    plain = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=0)).mean()
    sphere.shadow_terminator_shading_offset = shading_offset
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert not any("Shading Offset" in w for w in warnings), warnings
    prism = luminance(render_prism_rgba(fresh_scene, SAMPLES)).mean()
    cycles = luminance(render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=0)).mean()
    print(f"MEASURED Shading Offset {shading_offset}: Prism {prism:.5f}, Cycles {cycles:.5f} (Cycles at 0: "
          f"{plain:.5f}), ratio {prism / cycles:.4f}")
    assert cycles / plain < 0.95
    assert prism / cycles == pytest.approx(1.0, abs=0.015)


def test_a_shading_offset_on_hair_or_points_is_named(prism_addon):
    """Prism applies the Shading Offset to meshes only: on a hair or point-cloud piece the warning names the object,
    the value and how much darker Cycles shades light at 60° with it (at 0.2: cos(60° / 0.9) / cos 60° = 0.79, 21 %
    darker); a mesh gets its multiplier 1 / (1 - 0.2 / 2) and no warning."""
    from types import SimpleNamespace

    terminator = importlib.import_module(f"{prism_addon.__name__}.engine.export.shadow_terminator")
    strands = SimpleNamespace(name="Fur", shadow_terminator_geometry_offset=0.1, shadow_terminator_shading_offset=0.2)
    warnings = []
    assert terminator.terminator_offsets(strands, "MESH", warnings) == pytest.approx((0.1, 1.0 / 0.9))
    assert not warnings
    terminator.terminator_offsets(strands, "CURVES", warnings)
    assert len(warnings) == 1 and "Object 'Fur'" in warnings[0] and "Shading Offset 0.2" in warnings[0]
    assert "21 % darker" in warnings[0]


def test_the_object_panels_prism_honours_are_shown_for_prism(prism_addon, fresh_scene):
    """Blender's Object ▸ Shading ▸ Shadow Terminator panel (and its parent, which also holds Light Linking) list
    Prism among their engines, and Prism's Object ▸ Visibility panels (Cycles' Shadow Catcher, Holdout and Ray
    Visibility, whose own panels poll for Cycles alone) show for a mesh and draw."""
    from types import SimpleNamespace

    bpy.ops.mesh.primitive_cube_add()
    context = SimpleNamespace(engine="PRISM", object=bpy.context.active_object, scene=fresh_scene)
    for name in ("OBJECT_PT_shading", "OBJECT_PT_shadow_terminator", "PRISM_PT_object_visibility",
                 "PRISM_PT_object_ray_visibility"):
        panel = getattr(bpy.types, name)
        assert "PRISM" in panel.COMPAT_ENGINES and panel.poll(context), name
    drawn = []
    layout = SimpleNamespace(prop=lambda owner, name, **_: drawn.append(name), column=lambda **_: layout,
                             use_property_split=True, use_property_decorate=False)
    for name in ("PRISM_PT_object_visibility", "PRISM_PT_object_ray_visibility"):
        getattr(bpy.types, name).draw(SimpleNamespace(layout=layout), context)
    assert {"is_shadow_catcher", "is_holdout", "visible_camera", "visible_shadow", "visible_volume_scatter"} <= set(drawn)
