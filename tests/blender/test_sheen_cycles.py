"""Blender's sheen against Cycles in absolute luminance: spheres under a uniform white world
(``helpers.furnace_zoo``), a Principled BSDF with Sheen 1 on a dark base and a Sheen BSDF node
(Microfiber), white and tinted. Before the sheen was modelled Prism left it out (a white Sheen BSDF
rendered black, the Principled sheen at its dark base's level). Ratios measured are in docs/materials.md."""

from __future__ import annotations

import numpy as np

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.cycles_compare import LUMINANCE
from helpers.furnace_zoo import build_furnace_zoo, one_node, principled

DARK = (0.05, 0.05, 0.05)
PATCHES = [
    ("principled sheen 1, roughness 0.5, dark base",
     principled(Base_Color=DARK, Roughness=0.5, Sheen_Weight=1.0, Sheen_Roughness=0.5)),
    ("principled sheen 1, roughness 0.2, tinted, dark base",
     principled(Base_Color=DARK, Roughness=0.5, Sheen_Weight=1.0, Sheen_Roughness=0.2,
                Sheen_Tint=(0.9, 0.5, 0.2, 1.0))),
    ("sheen node white, roughness 0.5",
     one_node("ShaderNodeBsdfSheen", distribution="MICROFIBER", Color=(1.0, 1.0, 1.0), Roughness=0.5)),
    ("sheen node white, roughness 1",
     one_node("ShaderNodeBsdfSheen", distribution="MICROFIBER", Color=(1.0, 1.0, 1.0), Roughness=1.0)),
]
SAMPLES = 64
BOUNCES = 8


def patch_luminances(image, masks):
    luminance = image[..., :3] @ LUMINANCE
    return np.array([luminance[mask].mean() for mask in masks])


def test_sheen_matches_cycles_in_absolute_luminance(prism_addon, fresh_scene):
    masks = build_furnace_zoo(PATCHES)
    cycles = patch_luminances(render_cycles_rgba(fresh_scene, SAMPLES, 0, BOUNCES), masks)
    fresh_scene.prism.max_bounces = BOUNCES
    prism = patch_luminances(render_prism_rgba(fresh_scene, SAMPLES, 0), masks)
    ratios = {name: (round(float(p / c), 4), round(float(c), 4)) for (name, _), p, c in zip(PATCHES, prism, cycles)}
    print("prism/cycles, cycles luminance:", ratios)
    assert all(abs(r - 1.0) < 0.02 for r, _ in ratios.values()), ratios


def test_ashikhmin_velvet_renders_as_microfiber_with_a_warning(prism_addon, fresh_scene):
    import importlib

    import bpy

    build_furnace_zoo([("velvet", one_node("ShaderNodeBsdfSheen", distribution="ASHIKHMIN", Roughness=0.5))])
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    warnings = []
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    material = next(m for m in scene.materials if m.name == "velvet")
    assert [spec.kind for spec in material.shader.closures] == [6]  # bsdf.closure.SHEEN
    assert warnings == ["Material 'velvet': the 'Sheen BSDF' node (Sheen BSDF) uses the Ashikhmin distribution; "
                        "Prism renders the Microfiber sheen instead."]
