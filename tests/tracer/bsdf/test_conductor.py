"""Conductors: GGX visible-normal sampling against the pdf (chi-square), energy, mirror."""

import numpy as np
import pytest

from engine.tracer.bsdf import Conductor

from .bsdf_checks import albedo, chi2_sampling_test, direction, weight_matches_eval


def fresnel_one(cos_i, lam):
    return np.ones(lam.shape)


@pytest.mark.parametrize("alpha", [0.01, 0.2, 0.7])
@pytest.mark.parametrize("theta", [10.0, 60.0, 85.0])
def test_ggx_sampling_chi2(alpha, theta):
    assert chi2_sampling_test(Conductor(alpha, fresnel_one), direction(theta), n=200_000, bins=16) > 1e-3


@pytest.mark.parametrize("alpha", [0.01, 0.3, 1.0])
def test_energy_and_weights(alpha):
    b = Conductor(alpha, fresnel_one)
    for theta in (0.0, 45.0, 75.0, 89.0):
        a = albedo(b, direction(theta), n=50_000)
        assert a[0] <= 1.0 + 1e-9
        assert weight_matches_eval(b, direction(theta)) < 1e-6


def test_mirror_reflects_with_fresnel():
    b = Conductor(0.0, lambda c, lam: np.full(lam.shape, 0.9))
    assert b.delta
    wo = direction(40, 30)[None]
    s = b.sample(wo, np.full((1, 1), 500.0), np.zeros((1, 3)), np.zeros(1, int), np.zeros(1, bool))
    assert np.allclose(s.wi, direction(40, 210)[None]) and s.weight[0, 0] == pytest.approx(0.9) and s.delta[0]
