"""Blender's Principled layering with a constant specular layer (``ClosureSpec.layer``, applied per hit
from the closure rows): a white diffuse base under a dielectric GGX layer neither absorbs nor emits, so
in a white furnace the sphere renders as the sky. The layer takes its directional albedo, the diffuse
the rest: a view cosine taken from the wrong normal, or an albedo table read at the wrong place, shows
up at the sphere's grazing rim. (Single-scatter GGX loses < 0.1 % at these roughnesses.)"""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import CONDUCTOR, DIFFUSE, FRESNEL_DIELECTRIC
from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
from engine.tracer.materials.table import MAT_LAYERED, MAT_PROGRAM, build_materials
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Material
from engine.tracer.spectra.table import SpectrumTable

from .tracer_scenes import settings, sphere_under_sky

WHITE = Colour(rgb=(1.0, 1.0, 1.0))


def _layered(roughness, ior=1.5):
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    specular = ClosureSpec(CONDUCTOR, tint=WHITE, s0=WHITE, alpha=roughness**2, fresnel=FRESNEL_DIELECTRIC, eta=ior,
                           selection=f0)
    diffuse = ClosureSpec(DIFFUSE, tint=WHITE, layer=(ior, roughness, f0))
    return Material("layered", shader=ShaderProgram([specular, diffuse]))


def test_a_constant_layer_needs_no_program():
    table = build_materials([_layered(0.3)], {0}, SpectrumTable())
    assert table.arrays.flags[0] & MAT_LAYERED
    assert not table.arrays.flags[0] & MAT_PROGRAM


@pytest.mark.parametrize("roughness", [0.0, 0.2, 0.4])
def test_white_base_under_a_specular_layer_vanishes_in_the_furnace(roughness):
    s = settings(samples=64, samples_per_pass=64, max_bounces=8)
    scene = sphere_under_sky(size=16)
    scene.materials = [_layered(roughness)]
    with Renderer(scene, s) as r:
        r.render_pass()
        image = r.image_rgb().astype(np.float64)
        variance = r.variance_rgb().astype(np.float64)
    scene.triangles = scene.triangles[:0]
    scene.triangle_material = scene.triangle_material[:0]
    with Renderer(scene, s) as sky_renderer:
        sky_renderer.render_pass()
        sky = sky_renderer.image_rgb().astype(np.float64).mean((0, 1))
    mean = image.mean((0, 1)) / sky
    stderr = np.sqrt(variance.mean((0, 1)) / image[..., 0].size) / sky
    print(f"MEASURED layered furnace roughness {roughness}: {mean} ± {stderr}")
    assert np.all(np.abs(mean - 1.0) < 4 * stderr + 0.003), (mean, stderr)
    assert r.stats["nan_samples"] == 0
