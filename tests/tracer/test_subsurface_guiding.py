"""The random walk's guided directions (``subsurface.guiding``): the density integrates to 1 over the sphere,
the sampler draws cosines with exactly that density (chi-square), directions have the cosine they were drawn
with, and the diffusion length matches d'Eon & Křivánek's fit at known points."""

import math

import numpy as np
import pytest
from scipy import stats

from engine.tracer.jit import kernel
from engine.tracer.subsurface.guiding import (diffusion_length, guided_cosine, guided_direction, guided_fraction,
                                              guided_pdf)

ALPHAS = [0.2, 0.6, 0.95, 0.999999]


@kernel
def _draw(nu, log_ratio, n, u, out_mu, out_dot):
    for j in range(u.shape[0]):
        mu = guided_cosine(nu, log_ratio, u[j, 0])
        d = guided_direction(n, mu, u[j, 1])
        out_mu[j] = mu
        out_dot[j] = d[0] * n[0] + d[1] * n[1] + d[2] * n[2]


def _log_ratio(nu):
    return math.log((nu + 1.0) / (nu - 1.0))


def test_diffusion_length():
    # ν = 1 / √(1 − α^(2.44294 − 0.0215813 α + 0.578637 / α)), grows without bound as α → 1
    for alpha in ALPHAS:
        exponent = 2.44294 - 0.0215813 * alpha + 0.578637 / alpha
        assert diffusion_length(alpha) == pytest.approx(1.0 / math.sqrt(1.0 - alpha ** exponent), rel=1e-12)
    lengths = [diffusion_length(a) for a in ALPHAS]
    assert lengths == sorted(lengths) and lengths[0] > 1.0 and lengths[-1] > 500.0
    assert guided_fraction(0.0, False) == 0.5 and guided_fraction(0.8, False) == pytest.approx(1 - 0.8 ** 0.125)
    assert guided_fraction(0.8, True) == 0.75


@pytest.mark.parametrize("alpha", ALPHAS)
def test_guided_density_integrates_to_one(alpha):
    nu = diffusion_length(alpha)
    x, w = np.polynomial.legendre.leggauss(2000)
    total = 2 * math.pi * sum(wi * guided_pdf(nu, _log_ratio(nu), float(xi)) for xi, wi in zip(x, w))
    assert total == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("alpha", ALPHAS)
def test_guided_cosines_follow_their_density_chi_square(alpha):
    nu = diffusion_length(alpha)
    log_ratio = _log_ratio(nu)
    n_samples = 200_000
    u = np.random.default_rng(7).random((n_samples, 2))
    normal = np.array([0.48, -0.6, 0.64])
    mu, dots = np.empty(n_samples), np.empty(n_samples)
    _draw(nu, log_ratio, normal, u, mu, dots)
    np.testing.assert_allclose(dots, mu, atol=1e-12)  # the direction has the drawn cosine
    # Bins even in μ (not of equal probability, so the test does not replay the sampler's inverted CDF); each
    # bin's expected count from the density's integral, F(μ) = ln((ν + 1) / (ν − μ)) / ln((ν + 1) / (ν − 1)),
    # whose derivative is checked against ``guided_pdf``. Sparse bins are merged into their neighbours.
    edges = np.linspace(-1.0, 1.0, 41)
    cdf = np.log((nu + 1.0) / (nu - edges)) / log_ratio
    inner = np.linspace(-0.99, 0.99, 23)
    slope = (np.log((nu + 1.0) / (nu - inner - 1e-7)) - np.log((nu + 1.0) / (nu - inner + 1e-7))) / (2e-7 * log_ratio)
    np.testing.assert_allclose(slope, [2 * math.pi * guided_pdf(nu, log_ratio, m) for m in inner], rtol=1e-5)
    expected = np.diff(cdf) * n_samples
    observed, _ = np.histogram(mu, edges)
    keep = np.ones(len(edges), bool)
    running = 0.0
    for i, count in enumerate(expected[:-1]):  # drop inner edges until each bin expects at least 20
        running += count
        if running < 20.0:
            keep[i + 1] = False
        else:
            running = 0.0
    merged = np.add.reduceat(np.stack([observed, expected]), np.flatnonzero(keep[:-1]), axis=1)
    observed, expected = merged[0], merged[1] * n_samples / merged[1].sum()
    p = stats.chisquare(observed, expected).pvalue
    print(f"MEASURED guided cosines, alpha {alpha}: chi-square p = {p:.3f}, mean cosine {mu.mean():.4f}")
    assert p > 1e-3
    assert mu.mean() > 0.0  # leaning toward the surface
