"""The microfiber sheen lobe (``bsdf.sheen``) in isolation: the fitted table, the LTC density's
normalisation, its sampler (chi-square, pdf against evaluate) and the albedo it reflects (white furnace)."""

from types import SimpleNamespace

import numpy as np
import pytest
from numba import njit

from engine.tracer.bsdf.sheen import DEGENERATE, MIN_ROUGHNESS, load_sheen_table, lobe_pdf, lobe_sample, ltc_fit

from .bsdf_checks import chi2_sampling_test, direction

ROUGHNESS = [0.05, 0.3, 0.5, 0.75, 1.0]
THETAS = [0.0, 45.0, 75.0, 85.0]


@njit(cache=False)
def _sample_many(a, b, wo, u, wi, pdf):
    for i in range(len(u)):
        w, p = lobe_sample(a, b, (wo[i, 0], wo[i, 1], wo[i, 2]), u[i, 0], u[i, 1])
        wi[i, 0], wi[i, 1], wi[i, 2] = w
        pdf[i] = p


@njit(cache=False)
def _pdf_many(a, b, wo, wi, pdf):
    for i in range(len(wi)):
        pdf[i] = lobe_pdf(a, b, (wo[i, 0], wo[i, 1], wo[i, 2]), (wi[i, 0], wi[i, 1], wi[i, 2]))


class SheenLobe:
    """The lobe of one roughness behind ``bsdf_checks``' interface (weight = the fitted albedo)."""

    def __init__(self, roughness, wo):
        self.a, self.b, self.albedo = ltc_fit(load_sheen_table(), roughness, wo[2])

    def sample(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        wi, pdf = np.empty((n, 3)), np.empty(n)
        _sample_many(self.a, self.b, np.ascontiguousarray(wo), np.ascontiguousarray(u), wi, pdf)
        weight = np.where(pdf > 0, self.albedo, 0.0)[:, None]
        return SimpleNamespace(wi=wi, pdf=pdf, weight=weight, flags=np.zeros(n, np.int64))

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        pdf = np.empty(len(wi))
        _pdf_many(self.a, self.b, np.ascontiguousarray(wo), np.ascontiguousarray(wi), pdf)
        cos = np.abs(wi[:, 2])
        f = np.where(cos > 0, self.albedo * pdf / np.maximum(cos, 1e-300), 0.0)
        return f[:, None], pdf


def _sphere_quadrature(n=400):
    """Directions and solid-angle weights of a midpoint rule over the whole sphere (cos θ, φ)."""
    c = (np.arange(n) + 0.5) / n * 2.0 - 1.0
    p = (np.arange(2 * n) + 0.5) / (2 * n) * 2.0 * np.pi
    C, P = np.meshgrid(c, p, indexing="ij")
    s = np.sqrt(1.0 - C * C)
    wi = np.stack([s * np.cos(P), s * np.sin(P), C], -1).reshape(-1, 3)
    return wi, (2.0 / n) * (2.0 * np.pi / (2 * n))


def test_the_table_is_an_albedo():
    """Every fitted albedo lies in 0-1, and the rough fibres reflect more at normal view than the smooth."""
    table = load_sheen_table()
    assert table.albedo.shape == (32, 32)
    assert (table.albedo >= 0.0).all() and (table.albedo <= 1.0).all()
    assert table.albedo[-1, -1] > table.albedo[8, -1] > 0.0


def test_interpolation_is_cycles_bilinear():
    """On grid points the fit returns the table; between two it is their mean (Cycles' linear lookup)."""
    table = load_sheen_table()
    a, b, albedo = ltc_fit(table, 20 / 31, 10 / 31)
    assert (a, b, albedo) == pytest.approx((table.ltc_a[20, 10], table.ltc_b[20, 10], table.albedo[20, 10]))
    _, _, mid = ltc_fit(table, 20 / 31, 10.5 / 31)
    assert mid == pytest.approx(0.5 * (table.albedo[20, 10] + table.albedo[20, 11]))
    assert ltc_fit(table, 0.0, 0.5) == ltc_fit(table, MIN_ROUGHNESS, 0.5)
    assert ltc_fit(table, 0.0, 1.0)[2] == 0.0  # degenerate fit (smooth fibres seen head-on): no lobe


@pytest.mark.parametrize("roughness", ROUGHNESS)
def test_the_ltc_is_normalised(roughness):
    """D integrates to 1 over the sphere without the horizon clamp; with it (what is reflected) to ≤ 1."""
    wi, dw = _sphere_quadrature()
    for theta in THETAS:
        wo = direction(theta)
        lobe = SheenLobe(roughness, wo)
        if lobe.albedo < DEGENERATE:
            continue
        above = wi[wi[:, 2] > 0]
        _, pdf = lobe.eval(np.repeat(wo[None], len(above), 0), above, None)
        assert pdf.sum() * dw <= 1.0 + 2e-3, theta
        assert pdf.sum() * dw > 0.5, theta


@pytest.mark.parametrize("roughness", ROUGHNESS)
@pytest.mark.parametrize("theta", THETAS)
def test_chi_square_of_the_sampler(roughness, theta):
    wo = direction(theta)
    lobe = SheenLobe(roughness, wo)
    if lobe.albedo < DEGENERATE:
        pytest.skip("no lobe")
    assert chi2_sampling_test(lobe, wo, n=200_000) > 1e-3


@pytest.mark.parametrize("roughness", [0.3, 1.0])
def test_sampled_pdf_matches_evaluate(roughness):
    rng = np.random.default_rng(4)
    wo = direction(60.0, phi_deg=-110.0)
    lobe = SheenLobe(roughness, wo)
    s = lobe.sample(np.repeat(wo[None], 4000, 0), None, rng.random((4000, 3)), None, None)
    ok = s.pdf > 0
    _, pdf = lobe.eval(np.repeat(wo[None], ok.sum(), 0), s.wi[ok], None)
    assert np.allclose(pdf, s.pdf[ok], rtol=1e-9)
    assert (s.wi[ok, 2] > 0).all()


@pytest.mark.parametrize("roughness", ROUGHNESS)
def test_white_furnace_reflects_the_fitted_albedo(roughness):
    """Under uniform white light the lobe reflects albedo × (share of D above the horizon) ≤ albedo ≤ 1:
    the Monte Carlo mean weight and the quadrature of f cos agree."""
    rng = np.random.default_rng(5)
    wi_q, dw = _sphere_quadrature()
    for theta in THETAS:
        wo = direction(theta)
        lobe = SheenLobe(roughness, wo)
        n = 100_000
        s = lobe.sample(np.repeat(wo[None], n, 0), None, rng.random((n, 3)), None, None)
        reflected = s.weight[:, 0].mean()
        f, _ = lobe.eval(np.repeat(wo[None], len(wi_q), 0), wi_q, None)
        quadrature = (f[:, 0] * np.abs(wi_q[:, 2])).sum() * dw
        assert reflected <= lobe.albedo + 1e-12 <= 1.0 + 1e-12
        assert reflected == pytest.approx(quadrature, abs=3e-3), theta


def test_the_lobe_turns_with_the_viewer():
    """The fit is in a frame facing the viewer: rotating wo about the normal rotates the lobe with it."""
    lobe = SheenLobe(0.5, direction(60.0, 0.0))
    wi = direction(40.0, 150.0)
    turned = direction(40.0, 150.0 + 77.0)
    _, p0 = lobe.eval(direction(60.0, 0.0)[None], wi[None], None)
    _, p1 = lobe.eval(direction(60.0, 77.0)[None], turned[None], None)
    assert p0[0] == pytest.approx(p1[0], rel=1e-12) and p0[0] > 0
