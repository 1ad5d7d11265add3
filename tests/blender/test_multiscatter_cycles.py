"""Blender's Multiscatter GGX against Cycles in absolute luminance: a furnace zoo (``helpers.furnace_zoo``)
of Principled metals and dielectrics, a Glossy and a Glass, every node at its default distribution,
Multiscatter GGX. Single scattering rendered the white metal at 0.81× Cycles' luminance at roughness 0.6
and 0.38× at roughness 1 (the white dielectric 0.96×, the Glass 0.85× at 0.5); with energy compensation
each reflecting patch's mean luminance is within 1 % of Cycles' (measured over three seeds: within 0.1 %;
seed-to-seed noise 0.04-0.13 % a patch in either renderer at these sample counts, 0.2 % for the glass).

The Glass is also held to the closed form: a lossless sphere in a white furnace renders as the sky (the
glass ends the row, beside the white Glossy, which renders as the sky too). Prism's rough glass does, within
1 % (0.998 over three seeds); Cycles' renders at 0.992, and at up to 2 % below Prism's elsewhere
(docs/materials.md), likely because our integral of a rough interface seen from inside, which Prism's
glass tables hold, is darker near grazing than Cycles' table, so Cycles compensates less there."""

from __future__ import annotations

import numpy as np

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.cycles_compare import LUMINANCE
from helpers.furnace_zoo import build_furnace_zoo, one_node, principled

PATCHES = [
    ("metal 0.95, roughness 0.6", principled(Base_Color=(0.95, 0.95, 0.95), Metallic=1.0, Roughness=0.6)),
    ("metal 0.95, roughness 1", principled(Base_Color=(0.95, 0.95, 0.95), Metallic=1.0, Roughness=1.0)),
    ("dielectric white, roughness 1", principled(Base_Color=(1.0, 1.0, 1.0), Roughness=1.0)),
    ("glossy white, roughness 1", one_node("ShaderNodeBsdfAnisotropic", Color=(1.0, 1.0, 1.0), Roughness=1.0)),
    ("glass white, roughness 0.5", one_node("ShaderNodeBsdfGlass", Color=(1.0, 1.0, 1.0), Roughness=0.5, IOR=1.5)),
]
GLASS = "glass white, roughness 0.5"
SAMPLES = 64
BOUNCES = 16


def patch_luminances(image, masks):
    luminance = image[..., :3] @ LUMINANCE
    return np.array([luminance[mask].mean() for mask in masks])


def test_multiscatter_ggx_matches_cycles_in_absolute_luminance(prism_addon, fresh_scene):
    masks = build_furnace_zoo(PATCHES)
    cycles = patch_luminances(render_cycles_rgba(fresh_scene, SAMPLES, 0, BOUNCES), masks)
    fresh_scene.prism.max_bounces = BOUNCES
    prism = patch_luminances(render_prism_rgba(fresh_scene, SAMPLES, 0), masks)
    ratios = {name: round(float(p / c), 4) for (name, _), p, c in zip(PATCHES, prism, cycles)}
    reflecting = {name: r for name, r in ratios.items() if name != GLASS}
    assert all(abs(r - 1.0) < 0.01 for r in reflecting.values()), ratios
    glass = prism[[name for name, _ in PATCHES].index(GLASS)]
    assert abs(glass - 1.0) < 0.01 and abs(ratios[GLASS] - 1.0) < 0.025, (glass, ratios)


def test_the_distribution_decides_and_nothing_is_warned(prism_addon, fresh_scene):
    """Multiscatter GGX (Blender's default) compensates every lobe it offers, silently; GGX leaves single
    scattering, but for the coat, which Cycles always compensates."""
    import importlib

    import bpy

    build_furnace_zoo([("principled", principled(Metallic=0.5, Transmission_Weight=0.3, Coat_Weight=0.5,
                                                 Roughness=0.4))])
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")

    def closures():
        warnings = []
        scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
        material = next(m for m in scene.materials if m.name == "principled")
        return [(spec.kind, spec.multiscatter) for spec in material.shader.closures], warnings

    multi, warnings = closures()
    assert warnings == [] and [m for _, m in multi] == [True, True, True, True, False]  # coat, metal, glass,
    node = bpy.data.materials["principled"].node_tree.nodes["Principled BSDF"]  # specular, diffuse
    node.distribution = "GGX"
    single, warnings = closures()
    assert warnings == [] and [m for _, m in single] == [True, False, False, False, False]
