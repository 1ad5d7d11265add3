"""Glass: Fresnel split and Snell directions (smooth), GGX transmission sampling (rough)."""

import numpy as np
import pytest

from engine.tracer.scene import Material
from helpers.fresnel import fresnel_dielectric
from engine.tracer.spectra.glass import glass_by_name

from .bsdf_checks import MaterialBSDF, chi2_sampling_test, direction, weight_matches_eval


def glass(ior, alpha=0.0, **kw):
    return MaterialBSDF(Material("glass", kind="dielectric", ior=ior, roughness=np.sqrt(alpha), **kw))


@pytest.mark.parametrize("alpha", [0.01, 0.2, 0.6])
@pytest.mark.parametrize("theta,below", [(20.0, False), (70.0, False), (30.0, True), (60.0, True)])
def test_rough_sampling_chi2(alpha, theta, below):
    b = glass(1.5, alpha)
    assert chi2_sampling_test(b, direction(theta, below=below), n=200_000, bins=14) > 1e-3


@pytest.mark.parametrize("alpha", [0.05, 0.4])
def test_rough_energy_and_weights(alpha):
    b = glass(1.5, alpha)
    rng = np.random.default_rng(0)
    for theta, below in ((0.0, False), (50.0, False), (85.0, False), (20.0, True), (60.0, True)):
        wo = direction(theta, below=below)
        n = 50_000
        s = b.sample(np.repeat(wo[None], n, 0), np.full((n, 1), 550.0), rng.random((n, 3)),
                     np.zeros(n, int), np.zeros(n, bool))
        # flux form: radiance weights times eta'^2 (the 1/eta'^2 radiance scaling undone)
        assert (s.weight[:, 0] * s.eta_scale).mean() <= 1.0 + 0.01
        assert weight_matches_eval(b, wo) < 1e-6


def test_smooth_glass_fresnel_split_and_snell():
    eta = 1.5
    b = glass(eta)
    assert b.delta and not b.disperses
    wo = direction(50.0, 30.0)
    n = 100_000
    rng = np.random.default_rng(1)
    s = b.sample(np.repeat(wo[None], n, 0), np.full((n, 2), 550.0), rng.random((n, 3)), np.zeros(n, int),
                 np.zeros(n, bool))
    refl = s.wi[:, 2] > 0
    f = fresnel_dielectric(np.array([wo[2]]), np.array([eta]))[0]
    assert refl.mean() == pytest.approx(f, abs=0.005)
    t = s.wi[~refl][0]
    assert np.hypot(t[0], t[1]) * eta == pytest.approx(np.sin(np.radians(50.0)))
    assert np.allclose(s.weight[~refl], 1 / eta**2) and np.allclose(s.weight[refl], 1.0)
    # from inside beyond the critical angle: total internal reflection
    wo_in = direction(60.0, below=True)
    s = b.sample(wo_in[None], np.full((1, 1), 550.0), np.array([[0.99, 0.5, 0.5]]), np.zeros(1, int),
                 np.zeros(1, bool))
    assert s.wi[0, 2] < 0 and s.weight[0, 0] == pytest.approx(1.0)


def test_dispersive_glass_uses_hero_index():
    sf11 = glass_by_name("N-SF11")
    b = MaterialBSDF(Material("flint", kind="dielectric", glass="N-SF11"))
    assert b.disperses
    lam = np.array([[450.0, 650.0], [450.0, 650.0]])
    eta = b.eta(lam, np.array([0, 1]))
    assert eta[0] == pytest.approx(float(sf11.index(450.0))) and eta[1] == pytest.approx(float(sf11.index(650.0)))


@pytest.mark.parametrize("theta,below", [(30.0, False), (40.0, True)])
def test_rough_coated_glass_sampling_chi2_and_weights(theta, below):
    """The coating changes the reflect/refract choice (p = R of the film stack); sampling
    and pdf must still agree."""
    b = glass(1.6, 0.15, coating_thickness_nm=250.0, coating_ior=1.38)
    wo = direction(theta, below=below)
    assert chi2_sampling_test(b, wo, n=150_000, bins=12) > 1e-3
    assert weight_matches_eval(b, wo) < 1e-6


def test_index_below_one_refracts_away_and_reflects_totally_beyond_the_critical_angle():
    """An air bubble in water (relative index 1/1.33): Snell and Fresnel with eta < 1 from outside, total
    internal reflection from outside beyond asin(eta) ≈ 48.8°, and rough sampling still agrees with its pdf."""
    eta = 1.0 / 1.33
    b = glass(eta)
    n = 50_000
    rng = np.random.default_rng(2)
    wo = direction(30.0, 10.0)
    s = b.sample(np.repeat(wo[None], n, 0), np.full((n, 1), 550.0), rng.random((n, 3)), np.zeros(n, int),
                 np.zeros(n, bool))
    refl = s.wi[:, 2] > 0
    assert refl.mean() == pytest.approx(fresnel_dielectric(np.array([wo[2]]), np.array([eta]))[0], abs=0.005)
    t = s.wi[~refl][0]
    assert np.hypot(t[0], t[1]) * eta == pytest.approx(np.sin(np.radians(30.0)))  # bends away from the normal
    beyond = direction(60.0, 10.0)
    s = b.sample(np.repeat(beyond[None], 1000, 0), np.full((1000, 1), 550.0), rng.random((1000, 3)),
                 np.zeros(1000, int), np.zeros(1000, bool))
    assert np.all(s.wi[:, 2] > 0) and np.allclose(s.weight[:, 0], 1.0)
    assert chi2_sampling_test(glass(eta, 0.2), direction(35.0), n=150_000, bins=12) > 1e-3
