"""Material ▸ Prism ▸ Base Colour Spectrum = Measured replaces the base colour once, on the Principled BSDF
and the Diffuse BSDF alike: measured patches under a sun of a standard illuminant render, absolutely, at
the colours colour-science computes from the same spectra (``helpers.measured_chart`` has the physics)."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import render_linear_rgb
from helpers.measured_chart import (CHECKER, build_measured_chart, delta_e_2000, patch_names, rec709_to_xyz,
                                          reference_xyz, window_means)
from helpers.node_scenes import node, surface_material

SAMPLES = 16
SEED = 7


def _render_chart(scene, illuminant, patches):
    windows = build_measured_chart(scene, illuminant, patches)
    image = render_linear_rgb(scene, samples=SAMPLES, seed=SEED).astype(np.float64)
    return windows, window_means(image, windows)


def test_measured_and_file_reflectances_render_at_their_reflectance(fresh_scene, tmp_path):
    """Absolute, under luminance-normalised D65 at E = π W/m² (a patch's radiance is ρ(λ) S(λ)), with either node:
    a reflectance file of a flat 0.5 renders Rec.709 (0.5, 0.5, 0.5) (D65 is Rec.709's white); colour-checker
    patches render at colour-science's XYZ (Y 0.20 for neutral 5, 0.90 for white 9.5), not at their square."""
    flat = tmp_path / "flat_half.csv"
    flat.write_text("wavelength_nm,value\n360,0.5\n830,0.5\n")
    patches = [f"{CHECKER}: neutral 5 (.70 D)", f"{CHECKER}: white 9.5 (.05 D)"]
    windows, means = _render_chart(fresh_scene, "D65", [str(flat)] + patches)
    expected, _ = reference_xyz(patches, "D65")
    rendered = rec709_to_xyz(means)
    for (kind, source, _), rgb, xyz in zip(windows, means, rendered):
        if source == str(flat):
            assert np.allclose(rgb, 0.5, rtol=0.01), (kind, rgb)
            continue
        reference = expected[patches.index(source)]
        assert xyz[1] == pytest.approx(reference[1], rel=0.01), (kind, source, xyz, reference)
        assert np.allclose(xyz, reference, rtol=0.02), (kind, source, xyz, reference)


@pytest.mark.parametrize("illuminant", ["D65", "A", "FL2"])
def test_colour_checker_renders_colour_sciences_colours(fresh_scene, illuminant):
    """The 24 patches, on a Principled and on a Diffuse BSDF, against colour-science's XYZ of reflectance ×
    illuminant: CIEDE2000 at most 1 with no exposure scale."""
    patches = patch_names()
    windows, means = _render_chart(fresh_scene, illuminant, patches)
    expected, white = reference_xyz(patches, illuminant)
    delta_e = delta_e_2000(rec709_to_xyz(means), np.tile(expected, (2, 1)), white)
    figures = {kind: (float(delta_e[k * 24:(k + 1) * 24].max()), float(delta_e[k * 24:(k + 1) * 24].mean()))
               for k, kind in enumerate(("principled", "diffuse"))}
    print(f"\nMEASURED {CHECKER} under {illuminant}: " + "; ".join(
        f"{kind} CIEDE2000 max {worst:.2f} mean {mean:.2f}" for kind, (worst, mean) in figures.items()))
    worst = {f"{kind}: {patch}": round(float(e), 2) for (kind, patch, _), e in zip(windows, delta_e) if e > 1.0}
    assert delta_e.max() <= 1.0, (figures, worst)
    if illuminant == "D65":
        _cyan_is_out_of_gamut_as_measured(windows, means, patches, expected)


def _cyan_is_out_of_gamut_as_measured(windows, means, patches, expected):
    """The cyan patch under D65 lies outside Rec.709's gamut: colour-science's colour of it has red
    -0.033. Prism writes that negative red (scene-linear, as a spectral renderer measures it; Cycles, an
    RGB renderer, cannot leave the gamut), and does not clamp it to 0, which would shift the colour."""
    index = next(i for i, name in enumerate(patches) if name.endswith(": cyan"))
    reference_red = float(np.linalg.solve(rec709_to_xyz(np.eye(3)).T, expected[index])[0])
    assert reference_red < -0.02, reference_red
    for k in range(2):  # the Principled patch, then the Diffuse one
        assert windows[k * 24 + index][1] == patches[index]
        red = float(means[k * 24 + index][0])
        assert abs(red - reference_red) < 0.01, (windows[k * 24 + index][0], red, reference_red)


def _export(prism_addon, mat):
    """(tracer material, warnings) of ``mat`` as a render exports it."""
    materials = importlib.import_module(f"{prism_addon.__name__}.engine.export.materials")
    warnings = []
    return materials.export_material(mat, warnings), warnings


def _measured(mat, patch=f"{CHECKER}: moderate red"):
    mat.prism.reflectance_source, mat.prism.measured_reflectance = "MEASURED", patch
    return mat


def test_nodes_that_cannot_take_a_measured_reflectance_say_what_renders(prism_addon, fresh_scene):
    """Diffuse and Subsurface take the measured reflectance (in their tint only); a Glossy keeps its colour and a
    material with no node that takes it says so, naming the material; the panel shows the same."""
    from helpers.panel_layout import context, draw, labels

    panel = prism_addon.ui.panels_material.PRISM_PT_material_base_spectrum
    mixed = _measured(surface_material("Mixed", lambda nodes, link: _mix(nodes, link, "ShaderNodeBsdfDiffuse",
                                                                         "ShaderNodeBsdfGlossy")))
    exported, warnings = _export(prism_addon, mixed)
    diffuse = next(spec for spec in exported.shader.closures if spec.tint.spectrum is not None)
    assert diffuse.tint.spectrum.name == f"{CHECKER}: moderate red" and diffuse.s0 is None  # once, not twice
    assert any("Material 'Mixed': the 'Glossy BSDF' node" in w and "keeps its RGB colour" in w for w in warnings)
    assert not any("no node whose colour it replaces" in w for w in warnings), warnings
    assert "Replaces the colour of: Diffuse BSDF" in labels(draw(panel, context(fresh_scene, material=mixed)))

    glossy = _measured(surface_material("Shiny", lambda nodes, link: node(nodes, "ShaderNodeBsdfGlossy").outputs[0]))
    _, warnings = _export(prism_addon, glossy)
    assert any(w.startswith("Material 'Shiny': has a measured reflectance") and "renders the nodes' own colours" in w
               for w in warnings), warnings
    drawn = labels(draw(panel, context(fresh_scene, material=glossy)))
    assert any(text.startswith("No node here has a base colour it replaces") for text in drawn), drawn
    drawn = labels(draw(prism_addon.ui.panels_material.PRISM_PT_material, context(fresh_scene, material=glossy)))
    assert any("has a measured reflectance" in text for text in drawn), drawn

    skin = _measured(surface_material("Skin", lambda nodes, link: node(nodes,
                                                                       "ShaderNodeSubsurfaceScattering").outputs[0]))
    exported, _ = _export(prism_addon, skin)
    assert [spec.tint.spectrum is not None for spec in exported.shader.closures] == [True]


def _mix(nodes, link, first, second):
    mix = node(nodes, "ShaderNodeMixShader", Fac=0.5)
    link(node(nodes, first).outputs[0], mix.inputs[1])
    link(node(nodes, second).outputs[0], mix.inputs[2])
    return mix.outputs[0]


def test_principled_metal_glass_film_and_viewport_materials_with_a_measured_reflectance(prism_addon, fresh_scene):
    """The Principled metal takes it as its F0 (s0) unless Material ▸ Prism ▸ Metal names a measured metal, whose
    n stays; a Principled glass keeps its RGB tint, a thin film has no base colour, each with a warning; a
    material without nodes takes it in place of its viewport colour."""
    from engine.tracer.bsdf.closure import CONDUCTOR, DIFFUSE

    metal = _measured(surface_material("Brass", lambda nodes, link: node(nodes, "ShaderNodeBsdfPrincipled",
                                                                          Metallic=1.0).outputs[0]))
    exported, warnings = _export(prism_addon, metal)
    spec = next(s for s in exported.shader.closures if s.kind == CONDUCTOR and s.s0.spectrum is not None)
    assert spec.s0.spectrum.name == f"{CHECKER}: moderate red" and spec.tint.spectrum is None
    metal.prism.conductor = "AU"
    exported, warnings = _export(prism_addon, metal)
    assert any(s.s0 is not None and s.s0.spectrum == ("n", "Au") for s in exported.shader.closures)
    assert any("is a measured metal (Gold" in w for w in warnings), warnings

    f82 = _measured(surface_material("F82", lambda nodes, link: node(nodes, "ShaderNodeBsdfMetallic").outputs[0]))
    exported, _ = _export(prism_addon, f82)
    assert [s.s0.spectrum.name for s in exported.shader.closures] == [f"{CHECKER}: moderate red"]
    f82.node_tree.nodes["Metallic BSDF"].fresnel_type = "PHYSICAL_CONDUCTOR"
    _, warnings = _export(prism_addon, f82)
    assert any("'Metallic BSDF' node" in w and "its IOR and Extinction give its reflectance" in w for w in warnings)

    glass = _measured(surface_material("Glass", lambda nodes, link: node(nodes, "ShaderNodeBsdfPrincipled",
                                                                          Transmission_Weight=1.0).outputs[0]))
    _, warnings = _export(prism_addon, glass)
    assert any("Material 'Glass'" in w and "transmission is tinted by the Base Color" in w for w in warnings)

    film = _measured(surface_material("Bubble", lambda nodes, link: node(nodes, "ShaderNodeBsdfPrincipled").outputs[0]))
    film.prism.is_thin_film = True
    _, warnings = _export(prism_addon, film)
    assert any(w.startswith("Material 'Bubble': a free-standing thin film has no base colour") for w in warnings)

    plain = _measured(bpy.data.materials.new("Plain"))
    plain.use_nodes = False
    exported, _ = _export(prism_addon, plain)
    legacy = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.materials.legacy")
    closures = legacy.legacy_shader(exported).closures
    assert [c.kind for c in closures] == [DIFFUSE] and closures[0].s0.spectrum.name == f"{CHECKER}: moderate red"
    assert closures[0].tint is None
