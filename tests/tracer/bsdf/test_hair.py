"""Principled Hair (Chiang) as the kernels run it (``HAIR`` closures, ``materials.hair_setup``, ``bsdf.hair``,
``bsdf.dispatch``): energy conservation without absorption, the sampler against eval/pdf, reciprocity on the
specular cone, and the absorption's effect.

The tests put the fibre's tangent along the material's normal (z), so a direction's z is sin θ of the fibre's
frame and its azimuth about z the fibre's φ: eval's f · |z| is the model's F."""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import (C_HAIR_H, C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ, HAIR, SIGMA_ABSORPTION,
                                        SIGMA_COLOUR, SIGMA_MELANIN)
from engine.tracer.materials.shader import ClosureSpec, Colour, HairInputs, ShaderProgram
from engine.tracer.materials.table import MAT_HAIR
from engine.tracer.scene import Material

from .bsdf_checks import MaterialBSDF, chi2_sampling_test, direction, weight_matches_eval


def _hair(h, colour=None, absorption=None, **inputs):
    """A fibre's BSDF seen at offset ``h`` with its tangent along z."""
    hair = HairInputs(**inputs)
    spec = ClosureSpec(HAIR, s0=None if colour is None else Colour(rgb=colour),
                       s1=None if absorption is None else Colour(rgb=absorption), alpha=1.0, hair=hair)
    bsdf = MaterialBSDF(Material("hair", shader=ShaderProgram([spec])))
    rows = bsdf.table.arrays.closures
    rows[0, C_HAIR_H] = h
    rows[0, C_HAIR_TX], rows[0, C_HAIR_TY], rows[0, C_HAIR_TZ] = 0.0, 0.0, 1.0
    return bsdf


def _white(h, roughness, offset=0.0349066, coat=0.0):
    return _hair(h, sigma_mode=SIGMA_COLOUR, roughness=roughness, radial_roughness=roughness, offset=offset,
                 coat=coat)


def _sphere_integral(bsdf, wo, nx=900, nphi=1800, lam=550.0):
    """∫ f |cos| dω over the sphere: Gauss-Legendre in z (= sin θ), uniform in the periodic azimuth."""
    x, wx = np.polynomial.legendre.leggauss(nx)
    phi = (np.arange(nphi) + 0.5) * 2 * np.pi / nphi
    X, P = np.meshgrid(x, phi, indexing="ij")
    c = np.sqrt(1 - X * X)
    wi = np.stack([c * np.cos(P), c * np.sin(P), X], -1).reshape(-1, 3)
    n = len(wi)
    f, _ = bsdf.eval(np.repeat(wo[None], n, 0), wi, np.full((n, 1), lam))
    value = (f[:, 0] * np.abs(wi[:, 2])).reshape(nx, nphi)
    return float((value.sum(1) * wx).sum() * 2 * np.pi / nphi)


def test_the_flag_marks_the_material():
    assert _white(0.0, 0.3).table.arrays.flags[0] & MAT_HAIR


@pytest.mark.parametrize("roughness", [0.15, 0.3, 0.7])
@pytest.mark.parametrize("theta", [20.0, 80.0])
@pytest.mark.parametrize("h", [-0.7, 0.0, 0.45])
def test_white_furnace(roughness, theta, h):
    """Without absorption A0..A3 sum to 1 and every Mp, Np is normalised: the lobes integrate to 1 (measured:
    within 1.5e-3 of 1 for these; the largest error is the low-roughness log form of I0, Cycles' asymptotic
    expansion above 12)."""
    got = _sphere_integral(_white(h, roughness), direction(theta))
    assert got == pytest.approx(1.0, abs=3e-3)


def test_absorption_removes_light():
    wo = direction(60.0)
    white = _sphere_integral(_white(0.2, 0.3), wo, nx=400, nphi=800)
    brown = _sphere_integral(_hair(0.2, sigma_mode=SIGMA_MELANIN, melanin=0.8, melanin_redness=0.0), wo, nx=400,
                             nphi=800)
    dense = _sphere_integral(_hair(0.2, absorption=(50.0, 50.0, 50.0), sigma_mode=SIGMA_ABSORPTION), wo, nx=400,
                             nphi=800)
    assert brown < 0.5 * white
    # an opaque fibre reflects its R lobe only: the Fresnel reflectance at cos θo cos γo (IOR 1.55)
    from engine.tracer.bsdf.hair_chiang import fibre_geometry

    f = fibre_geometry(wo[2], 0.2, 1.55)[4]
    assert dense == pytest.approx(f, rel=5e-3)


@pytest.mark.parametrize("inputs", [dict(roughness=0.15), dict(roughness=0.3), dict(roughness=0.7),
                                    dict(roughness=0.3, coat=0.6), dict(roughness=0.2, offset=0.1)])
@pytest.mark.parametrize("theta", [25.0, 75.0])
def test_chi_square_and_weights(inputs, theta):
    inputs = dict(inputs)
    roughness = inputs.pop("roughness")
    bsdf = _hair(0.3, sigma_mode=SIGMA_MELANIN, melanin=0.5, roughness=roughness, radial_roughness=roughness,
                 **inputs)
    wo = direction(theta)
    assert chi2_sampling_test(bsdf, wo, n=200_000) > 1e-3
    assert weight_matches_eval(bsdf, wo) < 1e-6


def test_reciprocal_on_the_specular_cone():
    """With h = 0 and no cuticle tilt the lobes depend on θi and θo symmetrically where sin θi = -sin θo (the
    attenuation is a function of θo alone, so off the cone the model is not reciprocal, in Cycles too)."""
    rng = np.random.default_rng(4)
    bsdf = _hair(0.0, sigma_mode=SIGMA_MELANIN, melanin=0.4, roughness=0.3, radial_roughness=0.4, offset=0.0)
    n = 200
    s = rng.uniform(-0.95, 0.95, n)
    a, b = rng.uniform(0, 2 * np.pi, (2, n))
    c = np.sqrt(1 - s * s)
    wo = np.stack([c * np.cos(a), c * np.sin(a), s], -1)
    wi = np.stack([c * np.cos(b), c * np.sin(b), -s], -1)
    lam = np.full((n, 1), 600.0)
    f1, _ = bsdf.eval(wo, wi, lam)
    f2, _ = bsdf.eval(wi, wo, lam)
    assert np.allclose(f1, f2, rtol=1e-9, atol=0.0)
