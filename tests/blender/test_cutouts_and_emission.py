"""Cut-outs and emissive node materials through Blender: a leaf's alpha shapes its shadow; a scene lit only
by an Emission-shader plane is light-sampled and converges like an area light of the same power; a
Blackbody feeding an emission becomes a Planck spectrum."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.cycles_compare import LUMINANCE, normalised, relative_mse, render_cycles, render_prism
from helpers.node_scenes import black_world, camera, material, node, plane, surface_material


def _leaf_image(size=32):
    """An image whose alpha is a leaf: an ellipse with a notch, RGB green."""
    image = bpy.data.images.new("leaf", size, size, alpha=True)
    y, x = (np.mgrid[0:size, 0:size] + 0.5) / size - 0.5
    inside = (x / 0.45) ** 2 + (y / 0.25) ** 2 < 1.0
    inside &= ~((x > 0.2) & (np.abs(y) < 0.08))
    pixels = np.zeros((size, size, 4), np.float32)
    pixels[..., :3] = (0.1, 0.5, 0.1)
    pixels[..., 3] = inside
    image.pixels.foreach_set(pixels.ravel())
    return image, inside


def _leaf_material(image):
    mat, nodes, link = material("leaf")
    texture = nodes.new("ShaderNodeTexImage")
    texture.image, texture.interpolation = image, "Closest"
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled")
    bsdf.distribution = "GGX"
    link(texture.outputs["Color"], bsdf.inputs["Base Color"])
    link(texture.outputs["Alpha"], bsdf.inputs["Alpha"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _classify(inside, sun_angle, px, py):
    """0 leaf, 1 lit floor, 2 shadowed floor for camera rays through film points (px, py) (tangent units):
    the camera 8 m above the floor looks straight down; the leaf (2 m, texels ``inside``) is 1 m above it."""

    def opaque(x, y):
        tx, ty = np.floor((x + 1.0) / 2.0 * 32).astype(int), np.floor((y + 1.0) / 2.0 * 32).astype(int)
        ok = (tx >= 0) & (tx < 32) & (ty >= 0) & (ty < 32)
        out = np.zeros(np.shape(x), bool)
        out[ok] = inside[ty[ok], tx[ok]]
        return out

    leaf = opaque(7.0 * px, 7.0 * py)
    fx, fy = 8.0 * px, 8.0 * py
    shadow = opaque(fx + math.tan(sun_angle), fy)
    return np.where(leaf, 0, np.where(shadow, 2, 1))


def test_leaf_alpha_casts_a_leaf_shaped_shadow(prism_addon, fresh_scene):
    """A leaf (a plane whose Principled alpha is an image's alpha: an ellipse with a notch) 1 m above a floor,
    a sun 60° off vertical, a camera straight above: every pixel is the leaf, lit floor or shadow exactly
    as the leaf's opaque texels decide along the camera ray and the sun's ray, and the image matches
    Cycles'."""
    black_world()
    image, inside = _leaf_image()
    floor = surface_material("floor", lambda nodes, link: node(nodes, "ShaderNodeBsdfDiffuse",
                                                                Color=(0.8, 0.8, 0.8)).outputs[0])
    plane("floor", 8.0, mat=floor)
    plane("leaf", 2.0, location=(0.0, 0.0, 1.0), mat=_leaf_material(image))
    sun_angle = math.radians(60.0)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_euler = (0.0, sun_angle, 0.0)
    fresh_scene.collection.objects.link(sun)
    camera((0.0, 0.0, 8.0), (0.0, 0.0, 0.0), lens_mm=70.0, resolution=(64, 64))
    prism = render_prism(fresh_scene, 16, max_bounces=2)
    luminance = prism @ LUMINANCE
    half = 18.0 / 70.0
    centres = ((np.arange(64) + 0.5) / 64 * 2 - 1) * half
    px, py = np.meshgrid(centres, -centres)
    kinds = [_classify(inside, sun_angle, px + dx * half / 64, py + dy * half / 64)
             for dx in (-1, 1) for dy in (-1, 1)]
    settled = np.all([k == kinds[0] for k in kinds], axis=0)
    kind = np.where(settled, kinds[0], -1)
    lit, shadow = luminance[kind == 1], luminance[kind == 2]
    assert lit.size > 200 and shadow.size > 100 and (kind == 0).sum() > 200
    assert shadow.max() < 0.05 * lit.mean()  # the sun is blocked behind every opaque texel...
    assert lit.min() > 0.9 * lit.mean()  # ...and passes every transparent one (the notch included)
    cycles = render_cycles(fresh_scene, 16, max_bounces=2)
    assert float((prism @ LUMINANCE).mean() / (cycles @ LUMINANCE).mean()) == pytest.approx(1.0, abs=0.02)
    assert relative_mse(normalised(prism), normalised(cycles)) < 0.02


def _emission_lit_scene(panel_kind, power_w=200.0, size_m=1.0, height_m=2.0):
    black_world()
    floor = surface_material("floor", lambda nodes, link: node(nodes, "ShaderNodeBsdfDiffuse",
                                                                Color=(0.7, 0.7, 0.7)).outputs[0])
    plane("floor", 6.0, mat=floor)
    plane("wall", 6.0, location=(0.0, 3.0, 3.0), rotation=(math.pi / 2, 0.0, 0.0), mat=floor)
    if panel_kind == "emission":
        radiance = power_w / (math.pi * size_m * size_m)

        def build(nodes, link):
            # An Emission shader emits from both faces, an area light from its front only: black behind
            # (Geometry ▸ Backfacing) makes the powers equal.
            emission = node(nodes, "ShaderNodeEmission", Color=(1.0, 1.0, 1.0), Strength=radiance)
            black = node(nodes, "ShaderNodeBsdfDiffuse", Color=(0.0, 0.0, 0.0))
            geometry = nodes.new("ShaderNodeNewGeometry")
            mix = nodes.new("ShaderNodeMixShader")
            link(geometry.outputs["Backfacing"], mix.inputs["Fac"])
            link(emission.outputs[0], mix.inputs[1])
            link(black.outputs[0], mix.inputs[2])
            return mix.outputs[0]

        plane("panel", size_m, location=(0.0, 0.0, height_m), rotation=(math.pi, 0.0, 0.0),
              mat=surface_material("panel", build))
    else:
        light = bpy.data.lights.new("Panel", "AREA")
        light.shape, light.size, light.energy = "SQUARE", size_m, power_w
        lamp = bpy.data.objects.new("Panel", light)
        lamp.location = (0.0, 0.0, height_m)
        bpy.context.scene.collection.objects.link(lamp)
    camera((0.0, -5.0, 3.0), (0.0, 0.5, 0.5), lens_mm=35.0, resolution=(48, 36))


def test_emission_shader_plane_is_light_sampled_and_converges_like_an_area_light(prism_addon, fresh_scene):
    """Only an Emission-shader plane lights the scene: it renders (no 'no light' refusal) with light
    sampling of the emissive mesh, converges to the area-light reference (same power: radiance P / (π A)
    on the lit side) as 1/N, and at equal samples its error is within twice the area light's own."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    _emission_lit_scene("area")
    reference = render_prism(fresh_scene, 256, seed=7)
    area = render_prism(fresh_scene, 16, seed=1)
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    _emission_lit_scene("emission")
    tracer_scene = export.export_scene(bpy.context.evaluated_depsgraph_get())
    assert not tracer_scene.lights
    renderer_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    settings = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.settings").RenderSettings(
        samples=1, samples_per_pass=1, threads=2)
    with renderer_module.Renderer(tracer_scene, settings) as renderer:
        assert "emissive meshes" in renderer.strategy
    emission = render_prism(scene, 16, seed=1)
    longer = render_prism(scene, 64, seed=2)
    floor = slice(18, 36)
    for image in (emission, longer):
        assert (image[floor] @ LUMINANCE).mean() == pytest.approx((reference[floor] @ LUMINANCE).mean(), rel=0.01)
    error_emission = relative_mse(emission[floor], reference[floor])
    error_area = relative_mse(area[floor], reference[floor])
    assert error_emission < 2.0 * error_area + 1e-4, (error_emission, error_area)
    # 4 × the samples: the error (the reference's own noise, 1/16 of the 16-sample area render's, aside)
    # falls about 4 ×; a bias would keep it up.
    assert relative_mse(longer[floor], reference[floor]) < error_emission / 2.5


def test_blackbody_emission_is_a_planck_spectrum(prism_addon, fresh_scene):
    """A Blackbody node feeding an Emission exports as a blackbody spectrum of its temperature (not an RGB
    colour), and renders the colour Cycles gives it (luminance-normalised images within 3 %)."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    black_world()

    def build(nodes, link):
        emission = node(nodes, "ShaderNodeEmission", Strength=4.0)
        blackbody = node(nodes, "ShaderNodeBlackbody", Temperature=3200.0)
        link(blackbody.outputs["Color"], emission.inputs["Color"])
        return emission.outputs[0]

    plane("lamp", 1.0, location=(0.0, 0.0, 1.5), rotation=(math.pi, 0.0, 0.0), mat=surface_material("lamp", build))
    floor = surface_material("floor", lambda nodes, link: node(nodes, "ShaderNodeBsdfDiffuse",
                                                                Color=(0.8, 0.8, 0.8)).outputs[0])
    plane("floor", 4.0, mat=floor)
    camera((0.0, -3.0, 2.0), (0.0, 0.0, 0.5), lens_mm=35.0, resolution=(40, 30))
    lamp = next(m for m in export.export_scene(bpy.context.evaluated_depsgraph_get()).materials if m.name == "lamp")
    spectrum = lamp.shader.emission.spectrum
    assert (spectrum.kind, spectrum.temperature_k, lamp.shader.emission_strength) == ("blackbody", 3200.0, 4.0)
    prism_absolute, cycles_absolute = render_prism(fresh_scene, 64), render_cycles(fresh_scene, 64)
    ratio = float((prism_absolute @ LUMINANCE).mean() / (cycles_absolute @ LUMINANCE).mean())
    print("blackbody-lit floor, Prism / Cycles mean luminance:", round(ratio, 4))
    assert ratio == pytest.approx(1.0, abs=0.02)
    prism, cycles = normalised(prism_absolute), normalised(cycles_absolute)
    colour_p = prism.reshape(-1, 3).mean(axis=0)
    colour_c = cycles.reshape(-1, 3).mean(axis=0)
    assert colour_p == pytest.approx(colour_c, rel=0.03)
