"""Free-standing films and coatings: Airy reflectance routed through the BSDFs, energy."""

import numpy as np
import pytest

from engine.tracer.scene import Material
from helpers.thin_film import thin_film_reflectance

from .bsdf_checks import MaterialBSDF, albedo, direction


def _sample(b, wo, lam, n=100_000, seed=0):
    rng = np.random.default_rng(seed)
    lam = np.broadcast_to(lam, (n, len(lam))).copy()
    return b.sample(np.repeat(wo[None], n, 0), lam, rng.random((n, 3)), np.zeros(n, int), np.zeros(n, bool))


def test_soap_film_reflects_airy_fraction_and_transmits_undeviated():
    b = MaterialBSDF(Material("soap", kind="thin_film", film_thickness_nm=400.0, film_ior=1.33))
    assert b.delta
    wo = direction(35.0, 20.0)
    lam = np.array([450.0, 520.0, 610.0, 700.0])
    s = _sample(b, wo, lam)
    refl = s.wi[:, 2] > 0
    assert np.allclose(s.wi[~refl], -wo) and np.allclose(s.wi[refl], wo * [-1, -1, 1])
    r = thin_film_reflectance(wo[2], lam, 400.0, 1.0, 1.33, 1.0)
    assert refl.mean() == pytest.approx(r.mean(), abs=0.005)
    # per wavelength, E[weight] over both lobes splits into R_j and T_j = 1 - R_j
    assert np.allclose((s.weight * refl[:, None]).mean(0), r, atol=0.01)
    assert np.allclose(s.weight.mean(0), 1.0, atol=0.01)
    assert np.ptp(r) > 0.05  # interference colours


def test_coated_glass_conserves_energy_and_changes_reflectance():
    coated = MaterialBSDF(Material("bare", kind="dielectric", ior=1.5))
    mat = Material("ar", kind="dielectric", ior=1.5, coating_thickness_nm=100.0, coating_ior=1.38)
    ar = MaterialBSDF(mat)
    lam = np.array([450.0, 550.0, 650.0])
    wo = direction(10.0)
    for b in (coated, ar):
        s = _sample(b, wo, lam)
        assert np.allclose((s.weight * s.eta_scale[:, None]).mean(0), 1.0, atol=0.01)
    # a quarter-wave MgF2 layer at 552 nm is an anti-reflection coating
    r_ar = (_sample(ar, direction(0.0), lam).wi[:, 2] > 0).mean()
    r_bare = (_sample(coated, direction(0.0), lam).wi[:, 2] > 0).mean()
    assert r_ar < 0.5 * r_bare


def test_measured_and_coated_conductors():
    gold = MaterialBSDF(Material("gold", kind="conductor", conductor="Au", roughness=0.0))
    a = albedo(gold, direction(0.0), n=10, lam=np.array([450.0, 650.0]))
    assert a[0] < 0.5 < 0.9 < a[1]
    coated = MaterialBSDF(Material("tinted", kind="conductor", conductor="Au", coating_thickness_nm=250.0,
                                   coating_ior=1.5))
    rough = MaterialBSDF(Material("brushed", kind="conductor", base_color=(0.9, 0.6, 0.3), roughness=0.5,
                                  coating_thickness_nm=300.0))
    lam = np.linspace(400, 700, 7)
    for b in (coated, rough):
        for theta in (0.0, 60.0):
            w = albedo(b, direction(theta), n=20_000, lam=lam)
            assert np.all(w <= 1.0 + 1e-6) and np.all(w >= 0)
    assert not np.allclose(albedo(coated, direction(0.0), n=10, lam=lam), albedo(gold, direction(0.0), n=10, lam=lam))
