"""Henyey-Greenstein: the phase function integrates to 1 over the sphere, and the sampler draws directions
with exactly the density it reports (chi-square over cos θ and φ), for forward, backward and isotropic g."""

import math

import numpy as np
import pytest
from scipy import stats

from engine.tracer.jit import kernel
from engine.tracer.media.phase import hg_sample, hg_value

G_VALUES = [-0.7, -0.3, 0.0, 0.4, 0.9]


@kernel
def _draw(d_in, g, n, seed, out_cos, out_phi, out_pdf, out_value):
    np.random.seed(seed)
    t0 = (1.0, 0.0, 0.0) if abs(d_in[0]) < 0.9 else (0.0, 1.0, 0.0)
    for j in range(n):
        d, pdf = hg_sample(d_in, g, np.random.random(), np.random.random())
        c = d[0] * d_in[0] + d[1] * d_in[1] + d[2] * d_in[2]
        # φ around d_in, from a fixed reference vector
        rx = t0[1] * d_in[2] - t0[2] * d_in[1]
        ry = t0[2] * d_in[0] - t0[0] * d_in[2]
        rz = t0[0] * d_in[1] - t0[1] * d_in[0]
        r = math.sqrt(rx * rx + ry * ry + rz * rz)
        ax, ay, az = rx / r, ry / r, rz / r
        bx, by, bz = d_in[1] * az - d_in[2] * ay, d_in[2] * ax - d_in[0] * az, d_in[0] * ay - d_in[1] * ax
        out_cos[j] = c
        out_phi[j] = math.atan2(d[0] * bx + d[1] * by + d[2] * bz, d[0] * ax + d[1] * ay + d[2] * az)
        out_pdf[j] = pdf
        out_value[j] = hg_value(c, g)


@pytest.mark.parametrize("g", G_VALUES)
def test_phase_function_integrates_to_one(g):
    # ∫ p dω = 2π ∫ p(cos θ) d cos θ, by Gauss-Legendre on cos θ (the peak at g = 0.9 needs many nodes)
    x, w = np.polynomial.legendre.leggauss(4000)
    total = 2 * math.pi * sum(wi * hg_value(float(xi), g) for xi, wi in zip(x, w))
    assert total == pytest.approx(1.0, abs=2e-4)
    # mean cosine of HG is g
    mean_cos = 2 * math.pi * sum(wi * xi * hg_value(float(xi), g) for xi, wi in zip(x, w))
    assert mean_cos == pytest.approx(g, abs=2e-4)


@pytest.mark.parametrize("g", G_VALUES)
def test_sampler_matches_its_pdf_chi_square(g):
    n = 200_000
    d_in = (0.3, -0.5, math.sqrt(1 - 0.34))
    cos, phi, pdf, value = (np.empty(n) for _ in range(4))
    _draw(d_in, g, n, 7, cos, phi, pdf, value)
    assert np.allclose(pdf, value, rtol=1e-9)  # the reported pdf is the phase function (weight 1)
    # 16 cos θ bins equiprobable under the pdf (inverted CDF), x 8 φ bins
    edges = np.empty(17)
    for j, u in enumerate(np.linspace(0, 1, 17)):
        if abs(g) < 1e-3:
            edges[j] = 1 - 2 * u
        else:
            s = (1 - g * g) / (1 - g + 2 * g * u)
            edges[j] = (1 + g * g - s * s) / (2 * g)
    edges = np.sort(np.clip(edges, -1, 1))
    # bin probabilities computed independently from hg_value by quadrature
    probs = []
    for a, b in zip(edges[:-1], edges[1:]):
        x, w = np.polynomial.legendre.leggauss(200)
        xm = 0.5 * (b - a) * x + 0.5 * (a + b)
        probs.append(2 * math.pi * 0.5 * (b - a) * sum(wi * hg_value(float(xi), g) for xi, wi in zip(xm, w)))
    probs = np.repeat(np.array(probs)[:, None] / 8, 8, axis=1).ravel()
    counts, _, _ = np.histogram2d(cos, phi, bins=[edges, np.linspace(-math.pi, math.pi, 9)])
    assert probs.sum() == pytest.approx(1.0, abs=1e-4)
    chi2, p = stats.chisquare(counts.ravel(), probs / probs.sum() * n)
    assert p > 1e-3, (chi2, p)
