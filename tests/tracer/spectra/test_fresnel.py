import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from helpers.fresnel import (
    fresnel_conductor,
    fresnel_conductor_polarized,
    fresnel_dielectric,
    fresnel_dielectric_polarized,
    reflect,
    refract,
)


@pytest.mark.parametrize("n", [1.33, 1.5, 2.4, 0.75])
def test_normal_incidence(n):
    assert fresnel_dielectric(1.0, n) == pytest.approx(((n - 1) / (n + 1)) ** 2, rel=1e-12)


def test_grazing_incidence_reflects_everything():
    assert fresnel_dielectric(0.0, 1.5) == pytest.approx(1.0)
    assert fresnel_dielectric(1e-9, 1.5) == pytest.approx(1.0, abs=1e-8)


def test_published_values_at_45_degrees():
    r_s, r_p = fresnel_dielectric_polarized(np.cos(np.radians(45.0)), 1.5)
    assert r_s == pytest.approx(0.0920, abs=5e-5)
    assert r_p == pytest.approx(0.00846, abs=1e-5)  # published to 3 digits: 0.008466
    assert fresnel_dielectric(np.cos(np.radians(45.0)), 1.5) == pytest.approx(0.5 * (r_s + r_p))


def test_brewster_angle_has_no_p_reflection():
    for n in (1.33, 1.5, 1.9):
        r_s, r_p = fresnel_dielectric_polarized(np.cos(np.arctan(n)), n)
        assert r_p == pytest.approx(0.0, abs=1e-20)
        assert r_s > 0.01


def test_total_internal_reflection_and_inside_flip():
    n = 1.5
    critical = np.arcsin(1 / n)
    angles = np.array([critical - 0.01, critical + 0.001, critical + 0.3])
    # from inside the glass: eta = 1/n, or equivalently a negative cosine with eta = n
    r_inside = fresnel_dielectric(np.cos(angles), 1 / n)
    assert r_inside[0] < 1.0 and np.all(r_inside[1:] == 1.0)
    assert np.allclose(fresnel_dielectric(-np.cos(angles), n), r_inside)
    # below the critical angle, reciprocity: same reflectance from both sides for matching angles
    theta_t = np.arcsin(n * np.sin(angles[0]))
    assert fresnel_dielectric(np.cos(theta_t), n) == pytest.approx(r_inside[0], rel=1e-10)


def test_reflect():
    d = np.array([[1.0, 0.0, -1.0]]) / np.sqrt(2)
    r = reflect(d, np.array([[0.0, 0.0, 1.0]]))
    assert np.allclose(r, np.array([[1.0, 0.0, 1.0]]) / np.sqrt(2))


def test_refract_obeys_snell():
    rng = np.random.default_rng(5)
    n = 200
    normal = rng.normal(size=(n, 3))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d = np.where((np.sum(d * normal, axis=1) > 0)[:, None], -d, d)  # toward the surface
    eta = rng.uniform(0.6, 2.0, n)
    t, tir = refract(d, normal, eta)
    cos_i = -np.sum(d * normal, axis=1)
    sin_i = np.sqrt(1 - cos_i**2)
    ok = ~tir
    assert ok.sum() > 100 and tir.sum() > 5
    assert np.allclose(np.linalg.norm(t, axis=1), 1.0)
    cos_t = -np.sum(t * normal, axis=1)
    assert np.all(cos_t[ok] > 0)  # goes through
    sin_t = np.linalg.norm(np.cross(t, normal), axis=1)
    assert np.allclose(sin_i[ok], eta[ok] * sin_t[ok], atol=1e-12)
    # coplanar with the incident direction and the normal
    assert np.allclose(np.sum(np.cross(d, normal) * t, axis=1), 0.0, atol=1e-12)
    assert np.all(sin_i[tir] > eta[tir])
    assert np.allclose(t[tir], reflect(d[tir], normal[tir]))
    t_scalar, _ = refract(d[:3], normal[:3], 1.5)
    assert t_scalar.shape == (3, 3)


def test_conductor_reduces_to_dielectric_when_k_is_zero():
    cos = np.linspace(0.0, 1.0, 21)
    for n in (1.5, 2.4, 0.7):
        assert np.allclose(fresnel_conductor(cos, n, 0.0), fresnel_dielectric(cos, n), atol=1e-12)


def test_conductor_normal_incidence_and_grazing():
    n, k = 0.43, 2.455
    expected = ((n - 1) ** 2 + k**2) / ((n + 1) ** 2 + k**2)
    assert fresnel_conductor(1.0, n, k) == pytest.approx(expected, rel=1e-12)
    assert fresnel_conductor(0.0, n, k) == pytest.approx(1.0)
    r_s, r_p = fresnel_conductor_polarized(np.cos(np.radians(75.0)), n, k)
    assert r_p < r_s  # pseudo-Brewster dip in p
    # per-wavelength arrays broadcast against angles
    r = fresnel_conductor(np.array([[1.0], [0.5]]), np.array([0.2, 1.3]), np.array([3.0, 1.9]))
    assert r.shape == (2, 2)


def test_bad_input_raises():
    with pytest.raises(PrismInputError):
        fresnel_dielectric(np.nan, 1.5)
    with pytest.raises(PrismInputError):
        fresnel_dielectric(0.5, -1.0)
    with pytest.raises(PrismInputError):
        fresnel_dielectric(1.5, 1.5)
    with pytest.raises(PrismInputError):
        fresnel_conductor(0.5, 1.0, np.nan)
    with pytest.raises(PrismInputError):
        refract(np.array([[0.0, 0.0, -1.0]]), np.array([[0.0, 0.0, 1.0]]), np.nan)


def test_fast_conductor_form_matches_the_complex_one():
    rng = np.random.default_rng(9)
    cos = np.append(rng.random(500), [0.0, 1.0])
    n = np.append(rng.uniform(0.05, 3.0, 500), [1.0, 0.2])
    k = np.append(rng.uniform(0.0, 10.0, 500), [0.0, 3.0])
    for n_incident in (1.0, 1.33):
        r_s, r_p = fresnel_conductor_polarized(cos, n, k, n_incident)
        assert np.allclose(fresnel_conductor(cos, n, k, n_incident), 0.5 * (r_s + r_p), atol=1e-12)
