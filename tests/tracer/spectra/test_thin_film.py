import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from helpers.fresnel import fresnel_conductor, fresnel_dielectric
from helpers.thin_film import (
    thin_film_reflectance,
    thin_film_reflectance_transmittance,
    thin_film_transmittance,
)

COS = np.linspace(0.02, 1.0, 25)


def test_zero_thickness_is_the_bare_interface():
    r = thin_film_reflectance(COS, 550.0, 0.0, 1.0, 1.38, 1.5)
    assert np.allclose(r, fresnel_dielectric(COS, 1.5), atol=1e-12)
    r_metal = thin_film_reflectance(COS, 550.0, 0.0, 1.0, 1.38, 0.43 + 2.455j)
    assert np.allclose(r_metal, fresnel_conductor(COS, 0.43, 2.455), atol=1e-12)
    # a free-standing film of zero thickness is no film at all
    assert np.allclose(thin_film_reflectance(COS, 550.0, 0.0, 1.0, 1.33, 1.0), 0.0, atol=1e-15)


def test_film_of_the_substrate_index_is_invisible():
    r = thin_film_reflectance(COS, 500.0, 123.0, 1.0, 1.5, 1.5)
    assert np.allclose(r, fresnel_dielectric(COS, 1.5), atol=1e-12)


@pytest.mark.parametrize("n_incident, n_film, n_substrate", [(1.0, 1.33, 1.0), (1.0, 1.38, 1.52), (1.5, 1.0, 1.5),
                                                            (1.33, 2.0, 1.0)])
def test_energy_is_conserved_without_absorption(n_incident, n_film, n_substrate):
    wl = np.linspace(380.0, 780.0, 41)[:, None]
    thickness = np.array([0.0, 80.0, 300.0, 1200.0])[:, None, None]
    r, t = thin_film_reflectance_transmittance(COS, wl, thickness, n_incident, n_film, n_substrate)
    assert r.shape == (4, 41, 25)
    assert np.allclose(r + t, 1.0, atol=1e-12)
    assert np.allclose(t, thin_film_transmittance(COS, wl, thickness, n_incident, n_film, n_substrate))


def test_quarter_wave_film_first_maximum_at_4nd():
    n_film, d = 1.33, 110.0  # soap film in air
    wl = np.linspace(300.0, 1500.0, 120001)
    r = thin_film_reflectance(1.0, wl, d, 1.0, n_film, 1.0)
    assert wl[np.argmax(r)] == pytest.approx(4 * n_film * d, abs=0.02)
    # peak value: ((n_f^2 - n_0 n_s)/(n_f^2 + n_0 n_s))^2 with both sides air -> 4 r^2 / (1 + r^2)^2
    r0 = (n_film - 1) / (n_film + 1)
    assert r.max() == pytest.approx(4 * r0**2 / (1 + r0**2) ** 2, rel=1e-9)


def test_antireflection_coating_quarter_wave():
    n_sub = 1.52
    n_ar = np.sqrt(n_sub)  # ideal single-layer AR coating
    wl = 550.0
    r = thin_film_reflectance(1.0, wl, wl / (4 * n_ar), 1.0, n_ar, n_sub)
    assert r == pytest.approx(0.0, abs=1e-15)


def test_coating_on_metal_changes_its_colour():
    wl = np.linspace(400.0, 700.0, 31)
    bare = fresnel_conductor(1.0, 0.43, 2.455)
    coated = thin_film_reflectance(1.0, wl, 100.0, 1.0, 1.38, 0.43 + 2.455j)
    assert np.all((coated >= 0) & (coated <= 1))
    assert np.ptp(coated) > 0.01 and not np.allclose(coated, bare)


@pytest.mark.parametrize(
    "kwargs",
    [dict(thickness_nm=-1.0), dict(thickness_nm=np.nan), dict(wavelength_nm=0.0), dict(n_film=np.nan),
     dict(n_film=-1.33), dict(n_substrate=1.0 - 0.5j), dict(cos_theta_i=np.nan), dict(n_incident=0.0)],
)
def test_bad_input_raises(kwargs):
    args = dict(cos_theta_i=1.0, wavelength_nm=550.0, thickness_nm=300.0, n_incident=1.0, n_film=1.33, n_substrate=1.0)
    args.update(kwargs)
    with pytest.raises(PrismInputError):
        thin_film_reflectance(**args)


def _characteristic_matrix(cos0, wl, d, n0, n1, n2):
    """Independent reference: Abelès characteristic matrix with tilted admittances (Macleod).

    Macleod writes absorbing indices as n - ik (time factor e^{+iωt}); ours are n + ik, hence the conjugates.
    """
    n1, n2 = np.conj(complex(n1)), np.conj(complex(n2))
    s2 = n0**2 * (1 - cos0**2)
    q = [np.sqrt(np.asarray(n, complex) ** 2 - s2) for n in (n0, n1, n2)]
    out = []
    for pol in ("s", "p"):
        eta = q if pol == "s" else [complex(n) ** 2 / qq for n, qq in zip((n0, n1, n2), q)]
        delta = 2 * np.pi * q[1] * d / wl
        b = np.cos(delta) + 1j * np.sin(delta) / eta[1] * eta[2]
        c = 1j * eta[1] * np.sin(delta) + np.cos(delta) * eta[2]
        denominator = eta[0] * b + c
        out.append((abs((eta[0] * b - c) / denominator) ** 2, 4 * eta[0].real * eta[2].real / abs(denominator) ** 2))
    return 0.5 * (out[0][0] + out[1][0]), 0.5 * (out[0][1] + out[1][1])


@pytest.mark.parametrize("n2", [1.52, 0.43 + 2.455j, 1.0])
@pytest.mark.parametrize("angle_deg", [0.0, 35.0, 70.0])
def test_matches_the_characteristic_matrix_method(n2, angle_deg):
    cos0 = np.cos(np.radians(angle_deg))
    for wl, d, n1 in [(450.0, 120.0, 1.38), (600.0, 350.0, 2.1), (700.0, 40.0, 1.33)]:
        r, t = thin_film_reflectance_transmittance(cos0, wl, d, 1.0, n1, n2)
        r_ref, t_ref = _characteristic_matrix(cos0, wl, d, 1.0, n1, n2)
        assert r == pytest.approx(r_ref, abs=1e-12)
        assert t == pytest.approx(t_ref, abs=1e-12)
