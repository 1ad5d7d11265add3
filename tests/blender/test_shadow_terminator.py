"""Object ▸ Shading ▸ Shadow Terminator ▸ Geometry Offset, as Cycles 4.5 renders it: a coarse smooth-shaded sphere
under a low sun, Prism against Cycles in absolute light from the same scene, at the default offset (0.1), at 0 and
at 1. The Shading Offset, which Prism does not model, is named in a warning with what Cycles does with it.

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


def test_the_shading_offset_is_named_with_what_cycles_does(prism_addon, fresh_scene):
    """Prism does not model the Shading Offset; a warning names the object, the value and how much darker Cycles
    shades light at 60° with it (at 0.2: cos(60° / 0.9) / cos 60° = 0.79, 21 % darker), and nothing warns at 0."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    sphere = _coarse_sphere_under_low_sun()
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert not any("Shading Offset" in w for w in warnings), warnings
    sphere.shadow_terminator_shading_offset = 0.2
    warnings.clear()
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert any(f"Object '{sphere.name}'" in w and "Shading Offset 0.2 is not modelled" in w and "21 % darker" in w
               for w in warnings), warnings


def test_the_shadow_terminator_panel_is_shown_for_prism(prism_addon, fresh_scene):
    """Blender's Object ▸ Shading ▸ Shadow Terminator panel (and its parent, which also holds Light Linking) list
    Prism among their engines, so the offsets can be set; for an engine other than EEVEE the panel draws the
    Geometry and Shading Offsets, as for Cycles."""
    assert "PRISM" in bpy.types.OBJECT_PT_shading.COMPAT_ENGINES
    assert "PRISM" in bpy.types.OBJECT_PT_shadow_terminator.COMPAT_ENGINES
