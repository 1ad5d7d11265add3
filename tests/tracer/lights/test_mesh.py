"""Emissive triangles: area sampling against quadrature, pdf of hits, two-sided emission."""

import numpy as np
import pytest

from engine.tracer.lights.mesh import MeshEmitters


def test_emissive_quad_irradiance_and_pdf():
    verts = np.array([[-0.5, -0.5, 1.0], [0.5, -0.5, 1.0], [0.5, 0.5, 1.0], [-0.5, 0.5, 1.0], [5, 5, 5], [6, 5, 5],
                      [5, 6, 5]], np.float32)
    tris = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]])
    mesh = MeshEmitters(verts, tris, [0, 1], [2.0, 2.0], [0, 0], [lambda lam: np.ones(np.shape(lam))], 3)
    n = 200_000
    rng = np.random.default_rng(7)
    p = np.zeros((n, 3))
    wi, dist, li, pdf = mesh.sample(p, rng.random((n, 3)), np.full((n, 1), 500.0))
    est = li[:, 0] * wi[:, 2] / pdf
    # irradiance under a unit square of radiance 2 at height 1 (exact form for a square: 4 x corner patch)
    a = b = 0.5
    corner = (a / np.sqrt(1 + a * a) * np.arctan(b / np.sqrt(1 + a * a))
              + b / np.sqrt(1 + b * b) * np.arctan(a / np.sqrt(1 + b * b))) / (2 * np.pi)
    assert est.mean() == pytest.approx(2.0 * np.pi * 4 * corner, rel=0.005)
    # triangle 1 holds the points with y > x
    hit_tri = np.where(np.cross(np.array([1, 1, 0.0]), (p + dist[:, None] * wi) - verts[0])[:, 2] > 0, 1, 0)
    assert np.allclose(mesh.pdf(p, wi, dist, hit_tri), pdf, rtol=1e-6)
    # two-sided: radiance from below equals radiance from above; non-emissive triangle is black
    lam = np.full((3, 2), 550.0)
    assert np.allclose(mesh.radiance(np.array([0, 1, 2]), lam), [[2, 2], [2, 2], [0, 0]])
