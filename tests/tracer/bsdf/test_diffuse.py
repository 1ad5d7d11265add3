"""Lambertian BSDF: sampling against its pdf, energy, reciprocity."""

import numpy as np
import pytest

from engine.tracer.scene import Material

from .bsdf_checks import MaterialBSDF, albedo, chi2_sampling_test, direction, weight_matches_eval


def grey(value):
    return MaterialBSDF(Material("grey", base_color=(value,) * 3))


@pytest.mark.parametrize("theta", [0.0, 45.0, 80.0])
def test_cosine_sampling_chi2(theta):
    assert chi2_sampling_test(grey(0.7), direction(theta), n=100_000, bins=16) > 1e-3


def test_albedo_weights_and_reciprocity():
    b = grey(0.7)
    assert albedo(b, direction(30)) == pytest.approx([0.7])
    assert weight_matches_eval(b, direction(60)) < 1e-9
    wo, wi = direction(20, 10)[None], direction(70, 200)[None]
    lam = np.full((1, 1), 500.0)
    assert b.eval(wo, wi, lam)[0] == pytest.approx(b.eval(wi, wo, lam)[0])
    assert b.eval(wo, direction(30, 0, below=True)[None], lam)[0][0, 0] == 0.0
