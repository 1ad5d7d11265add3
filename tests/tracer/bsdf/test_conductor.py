"""Conductors: GGX visible-normal sampling against the pdf (chi-square), energy, mirror."""

import numpy as np
import pytest

from engine.tracer.scene import Material

from .bsdf_checks import MaterialBSDF, albedo, chi2_sampling_test, direction, weight_matches_eval


def metal(alpha, reflectance=1.0):
    """A conductor of GGX ``alpha`` with a grey Schlick reflectance (1: every Fresnel term is 1)."""
    return MaterialBSDF(Material("metal", kind="conductor", base_color=(reflectance,) * 3, roughness=np.sqrt(alpha)))


@pytest.mark.parametrize("alpha", [0.01, 0.2, 0.7])
@pytest.mark.parametrize("theta", [10.0, 60.0, 85.0])
def test_ggx_sampling_chi2(alpha, theta):
    assert chi2_sampling_test(metal(alpha), direction(theta), n=200_000, bins=16) > 1e-3


@pytest.mark.parametrize("alpha", [0.01, 0.3, 1.0])
def test_energy_and_weights(alpha):
    b = metal(alpha)
    for theta in (0.0, 45.0, 75.0, 89.0):
        a = albedo(b, direction(theta), n=50_000)
        assert a[0] <= 1.0 + 1e-9
        assert weight_matches_eval(b, direction(theta)) < 1e-6


def test_mirror_reflects_with_fresnel():
    b = metal(0.0, 0.9)
    assert b.delta
    wo = direction(40, 30)[None]
    s = b.sample(wo, np.full((1, 1), 500.0), np.zeros((1, 3)), np.zeros(1, int), np.zeros(1, bool))
    schlick = 0.9 + 0.1 * (1 - np.cos(np.radians(40))) ** 5
    assert np.allclose(s.wi, direction(40, 210)[None]) and s.weight[0, 0] == pytest.approx(schlick) and s.delta[0]
