"""Light tracing with node materials: light paths start from an emissive plane whose colour is a texture
and end on a checker-textured floor, as camera paths see them; the split (caustics by light tracing)
agrees with path tracing alone, block by block."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np

from helpers.node_scenes import black_world, camera, node, plane, surface_material, uv_sphere


def _blocks(image, size):
    h, w = image.shape[:2]
    return image[:h - h % size, :w - w % size].reshape(h // size, size, w // size, size, -1).mean((1, 3))


def _glass_ball_on_a_checker_under_a_textured_lamp():
    black_world()

    def floor(nodes, link):
        diffuse = node(nodes, "ShaderNodeBsdfDiffuse")
        checker = node(nodes, "ShaderNodeTexChecker", Scale=3.0, Color1=(0.85, 0.3, 0.15), Color2=(0.15, 0.4, 0.85))
        link(checker.outputs["Color"], diffuse.inputs["Color"])
        return diffuse.outputs[0]

    def lamp(nodes, link):
        emission = node(nodes, "ShaderNodeEmission", Strength=60.0)
        gradient = nodes.new("ShaderNodeTexGradient")
        ramp = nodes.new("ShaderNodeValToRGB")
        ramp.color_ramp.elements[0].color = (1.0, 0.35, 0.1, 1.0)
        ramp.color_ramp.elements[1].color = (0.2, 0.5, 1.0, 1.0)
        link(gradient.outputs["Fac"], ramp.inputs["Fac"])
        link(ramp.outputs["Color"], emission.inputs["Color"])
        return emission.outputs[0]

    def glass(nodes, link):
        bsdf = node(nodes, "ShaderNodeBsdfGlass", Roughness=0.0, IOR=1.5)
        bsdf.distribution = "GGX"
        return bsdf.outputs[0]

    plane("floor", 4.0, mat=surface_material("checker floor", floor))
    uv_sphere("ball", 0.5, (0.0, 0.0, 0.5), mat=surface_material("glass", glass), segments=64, rings=32)
    # The gradient runs along the lamp's generated coordinates: orange on one side, blue on the other.
    plane("lamp", 1.0, location=(0.3, 0.0, 2.5), rotation=(math.pi, 0.0, 0.0), mat=surface_material("lamp", lamp))
    camera((0.0, -3.0, 2.5), (0.0, 0.0, 0.3), lens_mm=50.0, resolution=(32, 24))


def _render(prism_addon, scene, **settings):
    renderer_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    settings_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.settings")
    r = renderer_module.Renderer(scene, settings_module.RenderSettings(threads=2, max_bounces=6, **settings))
    while r.samples_done < r.settings.samples:
        r.render_pass()
    return r


def test_light_paths_read_textured_emission_and_textured_receivers(prism_addon, fresh_scene):
    """Caustic light from a gradient-coloured Emission plane through a glass ball onto a checker floor:
    light tracing supplies a large share of the caustic, and the image agrees with path tracing alone
    (4.5 standard errors per 4 x 4 block, 3.5 in the caustic) — a light path taking the lamp's constant
    colour, or the floor's untextured rows, would differ there by far more."""
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    _glass_ball_on_a_checker_under_a_textured_lamp()
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get())
    reference = _render(prism_addon, scene, samples=2048, samples_per_pass=512, light_tracing="off", seed=7)
    split = _render(prism_addon, scene, samples=512, samples_per_pass=256, light_tracing="on", seed=8)
    assert "caustics by light tracing" in split.strategy and split.stats["light_splats"] > 10_000
    a, b = (_blocks(r.image_rgb().astype(np.float64), 4) for r in (reference, split))
    var = sum(_blocks(r.variance_rgb().astype(np.float64), 4) / 16 for r in (reference, split))
    z = (a - b) / np.sqrt(var + 1e-12)
    film = split.film
    light_part = _blocks((film._light_sum / film.light_paths).reshape(film.height, film.width, 3), 4)
    caustic = light_part.mean(-1) > 0.25 * b.mean(-1)
    assert caustic.sum() >= 2, light_part.mean(-1) / b.mean(-1)
    assert np.all(np.abs(z) < 4.5), z
    assert np.abs(z[caustic]).max() < 3.5 and abs(z.mean()) < 0.5, (z.mean(), z[caustic])
