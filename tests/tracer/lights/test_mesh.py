"""Emissive triangles: area sampling against the closed form, pdf of hits, two-sided emission."""

import numpy as np
import pytest

from engine.tracer.scene import Camera, Material, SpectrumSpec

from ..tracer_scenes import make_scene
from .light_checks import SceneLights


def test_emissive_quad_irradiance_and_pdf():
    quad_v = np.array([[-0.5, -0.5, 1.0], [0.5, -0.5, 1.0], [0.5, 0.5, 1.0], [-0.5, 0.5, 1.0]])
    other_v = np.array([[5, 5, 5], [6, 5, 5], [5, 6, 5.0]])
    glow = Material("glow", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=2.0)
    scene = make_scene([(quad_v, np.array([[0, 1, 2], [0, 2, 3]]), 0), (other_v, np.array([[0, 1, 2]]), 1)],
                       [glow, Material("plain")], Camera("c", np.eye(4), (1, 1)))
    lights = SceneLights(scene)
    mesh = lights.arrays.mesh
    assert mesh.triangle.tolist() == [0, 1] and mesh.of_triangle.tolist() == [0, 1, -1]
    n = 200_000
    p = np.zeros((n, 3))
    s = lights.sample(p, np.random.default_rng(7).random((n, 3)), 500.0)
    white = lights.spectra
    from engine.tracer.spectra.table import spectrum_value

    radiance = 2.0 * spectrum_value(white, int(lights.materials.emission_spectrum[0]), 500.0)
    assert np.allclose(s.li, radiance)
    est = s.li / radiance * 2.0 * s.wi[:, 2] / s.pdf
    # irradiance under a unit square of radiance 2 at height 1 (exact form for a square: 4 x corner patch)
    a = b = 0.5
    corner = (a / np.sqrt(1 + a * a) * np.arctan(b / np.sqrt(1 + a * a))
              + b / np.sqrt(1 + b * b) * np.arctan(a / np.sqrt(1 + b * b))) / (2 * np.pi)
    assert est.mean() == pytest.approx(2.0 * np.pi * 4 * corner, rel=0.005)
    # triangle 1 holds the points with y > x; its pdf for hits matches the sampling density
    hit_tri = np.where(np.cross(np.array([1, 1, 0.0]), (p + s.dist[:, None] * s.wi) - quad_v[0])[:, 2] > 0, 1, 0)
    assert np.allclose(lights.emitter_pdf(hit_tri, s.wi, s.dist), s.pdf, rtol=1e-6)
    # two-sided: sampled from above the quad too; the plain triangle never emits
    above = lights.sample(np.array([[0.0, 0.0, 2.0]]), np.array([[0.3, 0.6, 0.2]]), 500.0)
    assert above.pdf[0] > 0 and above.li[0] == pytest.approx(radiance)
    assert lights.emitter_pdf([2], s.wi[:1], s.dist[:1])[0] == 0.0
