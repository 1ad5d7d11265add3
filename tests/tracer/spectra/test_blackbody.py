import numpy as np
import pytest
from scipy import constants, optimize

from engine.tracer.spectra import cie
from engine.tracer.spectra.blackbody import (
    MAX_TEMPERATURE_K,
    MIN_TEMPERATURE_K,
    blackbody_luminance,
    planck_spectral_radiance,
)
from engine.tracer.errors import PrismInputError
from engine.tracer.spectra.wavelengths import sample_visible_wavelengths
from helpers.spectral_oracles import blackbody_luminance_normalised

WIEN_NM_K = 2.897771955e6


@pytest.mark.parametrize("temperature_k", [1000.0, 3000.0, 5772.0, 40000.0])
def test_wien_displacement(temperature_k):
    guess = WIEN_NM_K / temperature_k
    result = optimize.minimize_scalar(
        lambda wl: -planck_spectral_radiance(wl, temperature_k), bounds=(0.5 * guess, 2 * guess), method="bounded",
        options={"xatol": 1e-6 * guess},
    )
    assert result.x * temperature_k == pytest.approx(WIEN_NM_K, rel=1e-3)


def test_spot_value_against_codata_planck():
    h, c, k = constants.h, constants.c, constants.k
    wavelength_m, temperature_k = 550e-9, 5000.0
    expected_per_m = 2 * h * c**2 / wavelength_m**5 / np.expm1(h * c / (wavelength_m * k * temperature_k))
    assert planck_spectral_radiance(550.0, temperature_k) == pytest.approx(expected_per_m * 1e-9, rel=1e-12)


def test_no_overflow_and_broadcasting():
    radiance = planck_spectral_radiance(np.array([1.0, 10.0, 360.0, 830.0, 1e7]), np.array([[1000.0], [40000.0]]))
    assert radiance.shape == (2, 5)
    assert np.all(np.isfinite(radiance)) and np.all(radiance >= 0)
    assert radiance[0, 0] == 0.0  # exp(14 million) is not representable: exactly 0, no warning
    assert radiance[0, 2] > 0


def test_luminance_normalisation_keeps_brightness():
    for temperature_k in (2000.0, 10000.0):
        assert cie.spectrum_luminance(lambda wl: blackbody_luminance_normalised(wl, temperature_k)) == pytest.approx(
            1.0, rel=1e-9
        )
    # the same through the path tracer's estimator, with stratified wavelengths
    n = 4096
    wavelength_nm, pdf = sample_visible_wavelengths((np.arange(n) + 0.5) / n, 4)
    y = [
        cie.spectral_samples_to_xyz(blackbody_luminance_normalised(wavelength_nm, t), wavelength_nm, pdf).mean(0)[1]
        for t in (2000.0, 10000.0)
    ]
    assert y[0] == pytest.approx(y[1], rel=1e-3) and y[0] == pytest.approx(1.0, rel=1e-3)
    # the colour does change: 2000 K is reddish, 10000 K bluish
    xyz = [cie.spectrum_to_xyz(lambda wl, t=t: blackbody_luminance_normalised(wl, t)) for t in (2000.0, 10000.0)]
    rgb = cie.xyz_to_linear_rec709(np.array(xyz))
    assert rgb[0, 0] > rgb[0, 2] and rgb[1, 2] > rgb[1, 0]


def test_vectorised_temperatures():
    t = np.array([2000.0, 6500.0, 2000.0])
    values = blackbody_luminance_normalised(550.0, t)
    assert values.shape == (3,) and values[0] == values[2]
    assert np.allclose(blackbody_luminance(t[:2]), [planck_spectral_radiance(550.0, t[0]) / values[0],
                                                    planck_spectral_radiance(550.0, t[1]) / values[1]])


@pytest.mark.parametrize("temperature_k", [500.0, 999.9, 40000.1, np.nan, np.inf, -6500.0])
def test_out_of_range_temperature_raises(temperature_k):
    with pytest.raises(PrismInputError, match="outside 1000–40000 K"):
        blackbody_luminance_normalised(550.0, temperature_k)
    with pytest.raises(PrismInputError):
        planck_spectral_radiance(550.0, np.array([6500.0, temperature_k]))
    assert MIN_TEMPERATURE_K == 1000 and MAX_TEMPERATURE_K == 40000


def test_bad_wavelength_raises():
    with pytest.raises(PrismInputError):
        planck_spectral_radiance(np.nan, 6500.0)
    with pytest.raises(PrismInputError):
        planck_spectral_radiance(-5.0, 6500.0)


@pytest.mark.filterwarnings("ignore")
def test_chromaticity_matches_colour_science():
    """Independent check of Planck + CMF integration: colour's own blackbody and integration."""
    import colour

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    for temperature_k in (2000.0, 6504.0, 15000.0):
        sd = colour.sd_blackbody(temperature_k, colour.SpectralShape(360, 830, 1))
        expected = colour.XYZ_to_xy(colour.sd_to_XYZ(sd, cmfs, method="Integration"))
        xyz = cie.spectrum_to_xyz(lambda wl, t=temperature_k: blackbody_luminance_normalised(wl, t))
        assert np.allclose(xyz[:2] / xyz.sum(), expected, atol=2e-5)
