"""The sheen as the kernels run it (``SHEEN`` closures, ``materials.sheen_setup``, ``bsdf.dispatch``): the
tint carries the fitted albedo, sampling is exact, and it mixes with other closures."""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import DIFFUSE, SHEEN
from engine.tracer.bsdf.sheen import load_sheen_table, ltc_fit
from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
from engine.tracer.materials.table import MAT_SHEEN
from engine.tracer.scene import Material

from .bsdf_checks import MaterialBSDF, albedo, chi2_sampling_test, direction, weight_matches_eval

WHITE = Colour(rgb=(1.0, 1.0, 1.0))


def _sheen(roughness, tint=WHITE):
    return ClosureSpec(SHEEN, tint=tint, alpha=roughness)


def _bsdf(*specs):
    return MaterialBSDF(Material("sheen", shader=ShaderProgram(list(specs))))


def _hemisphere_share(roughness, wo, n=400):
    """∫ D over the upper hemisphere (midpoint rule), the share of the fitted albedo that is reflected."""
    from .test_sheen import SheenLobe, _sphere_quadrature

    wi, dw = _sphere_quadrature(n)
    wi = wi[wi[:, 2] > 0]
    _, pdf = SheenLobe(roughness, wo).eval(np.repeat(wo[None], len(wi), 0), wi, None)
    return pdf.sum() * dw


def test_the_flag_marks_the_material():
    assert _bsdf(_sheen(0.5)).table.arrays.flags[0] & MAT_SHEEN
    assert not _bsdf(ClosureSpec(DIFFUSE, s0=WHITE)).table.arrays.flags[0] & MAT_SHEEN


@pytest.mark.parametrize("roughness", [0.1, 0.5, 1.0])
@pytest.mark.parametrize("theta", [0.0, 50.0, 80.0])
def test_white_sheen_reflects_its_fitted_albedo(roughness, theta):
    """Mean sample weight = fitted albedo × share of the LTC above the horizon (≤ 1)."""
    wo = direction(theta)
    expected = ltc_fit(load_sheen_table(), roughness, wo[2])[2] * _hemisphere_share(roughness, wo)
    got = albedo(_bsdf(_sheen(roughness)), wo, n=100_000)[0]
    assert got == pytest.approx(expected, abs=3e-3)
    assert got <= 1.0


@pytest.mark.parametrize("roughness", [0.2, 0.6, 1.0])
@pytest.mark.parametrize("theta", [10.0, 70.0])
def test_chi_square_through_dispatch(roughness, theta):
    wo = direction(theta)
    assert chi2_sampling_test(_bsdf(_sheen(roughness)), wo, n=200_000) > 1e-3


def test_sheen_over_diffuse_mixes_exactly():
    """Two closures: weights agree with evaluate (one-sample MIS over closures) and the mixture's sampler passes."""
    b = _bsdf(_sheen(0.4, Colour(rgb=(0.8, 0.3, 0.2))), ClosureSpec(DIFFUSE, s0=Colour(rgb=(0.1, 0.1, 0.1))))
    wo = direction(65.0)
    assert weight_matches_eval(b, wo) < 1e-6
    assert chi2_sampling_test(b, wo, n=200_000) > 1e-3
