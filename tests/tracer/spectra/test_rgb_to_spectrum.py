import numpy as np
import pytest

from engine.tracer.spectra import cie
from engine.tracer.errors import PrismInputError
from engine.tracer.spectra.rgb_to_spectrum import (
    RGBEmission,
    d65_relative_power,
    evaluate_sigmoid_polynomial,
    reflectance_coefficients,
    white_rgb,
)
from engine.tracer.spectra.wavelengths import sample_visible_wavelengths
from engine.tracer.spectra.trapezoid import trapezoid

WAVELENGTHS_NM = np.arange(360.0, 830.5, 1.0)


def _reflectance_to_rgb(coefficients):
    """Independent of the module's kernel: trapezoid of R·D65·cmf, Y(D65) = 1, to Rec.709."""
    reflectance = evaluate_sigmoid_polynomial(coefficients, np.broadcast_to(WAVELENGTHS_NM, coefficients.shape[:-1] + WAVELENGTHS_NM.shape))
    power = d65_relative_power(WAVELENGTHS_NM)
    cmf = cie.cie_xyz_cmf(WAVELENGTHS_NM)
    xyz = trapezoid(reflectance[..., None] * (power[:, None] * cmf), WAVELENGTHS_NM, axis=-2)
    return cie.xyz_to_linear_rec709(xyz / trapezoid(power * cmf[:, 1], WAVELENGTHS_NM))


def test_white_and_black_are_exact():
    wl = np.linspace(300.0, 900.0, 601)
    coefficients = reflectance_coefficients(np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]))
    spectra = evaluate_sigmoid_polynomial(coefficients, np.broadcast_to(wl, (2, wl.size)))
    assert np.all(spectra[0] == 1.0)
    assert np.all(spectra[1] == 0.0)


def test_gray_axis_is_flat():
    coefficients = reflectance_coefficients(np.array([0.18, 0.18, 0.18]))
    spectrum = evaluate_sigmoid_polynomial(coefficients, WAVELENGTHS_NM)
    assert np.allclose(spectrum, 0.18, rtol=1e-12)


def test_round_trip_across_the_gamut():
    g = np.linspace(0.0, 1.0, 11)
    rgb = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    coefficients = reflectance_coefficients(rgb)
    assert coefficients.shape == rgb.shape
    back = _reflectance_to_rgb(coefficients)
    error = np.abs(back - rgb).max()
    assert error < 0.01, error
    # measured: the residual is the D65-table vs BT.709 white point mismatch only (< 3e-4)
    assert np.abs(back - rgb * white_rgb()).max() < 1e-5
    assert np.allclose(white_rgb(), 1.0, atol=5e-4)


@pytest.mark.filterwarnings("ignore")
def test_round_trip_against_colour_science_integration():
    import colour

    rgb = np.array([[0.2, 0.5, 0.8], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.05, 0.02, 0.01]])
    coefficients = reflectance_coefficients(rgb)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    for c, target in zip(coefficients, rgb):
        sd = colour.SpectralDistribution(evaluate_sigmoid_polynomial(c, WAVELENGTHS_NM), WAVELENGTHS_NM)
        xyz = colour.sd_to_XYZ(sd, cmfs, colour.SDS_ILLUMINANTS["D65"]) / 100.0
        assert np.allclose(cie.xyz_to_linear_rec709(xyz), target, atol=0.01)


def test_broadcasting_of_sigmoid_polynomial():
    coefficients = reflectance_coefficients(np.array([[0.8, 0.2, 0.1], [0.1, 0.3, 0.9]]))
    wl = np.array([[450.0, 650.0], [450.0, 650.0]])
    values = evaluate_sigmoid_polynomial(coefficients, wl)
    assert values.shape == (2, 2)
    assert values[0, 1] > values[0, 0] and values[1, 0] > values[1, 1]  # red is red, blue is blue
    assert np.all((values >= 0) & (values <= 1))


@pytest.mark.parametrize("bad", [(np.nan, 0.5, 0.5), (0.5, -0.1, 0.5), (1.2, 0.5, 0.5), (0.5, np.inf, 0.5)])
def test_reflectance_rejects_bad_colours(bad):
    with pytest.raises(PrismInputError):
        reflectance_coefficients(np.array(bad))


def test_emission_white_renders_white():
    n = 4096
    wavelength_nm, pdf = sample_visible_wavelengths((np.arange(n) + 0.5) / n, 4)
    for rgb in [(1.0, 1.0, 1.0), (3.0, 0.5, 0.2), (0.0, 0.0, 0.25)]:
        emission = RGBEmission(rgb)
        xyz = cie.spectral_samples_to_xyz(emission.evaluate(wavelength_nm), wavelength_nm, pdf).mean(axis=0)
        assert np.allclose(cie.xyz_to_linear_rec709(xyz), rgb, atol=1e-3 * max(rgb)), rgb
    white = RGBEmission((1.0, 1.0, 1.0))
    assert cie.spectrum_luminance(white.evaluate) == pytest.approx(1.0, rel=1e-9)
    assert np.all(RGBEmission((0.0, 0.0, 0.0)).evaluate(wavelength_nm) == 0.0)


def test_emission_rejects_bad_colours():
    with pytest.raises(PrismInputError):
        RGBEmission((np.nan, 1.0, 1.0))
    with pytest.raises(PrismInputError):
        RGBEmission((-1.0, 1.0, 1.0))


def test_float32_round_off_above_one_is_accepted():
    coefficients = reflectance_coefficients(np.array([1.0000001, 0.5, 0.25]))
    assert np.allclose(coefficients, reflectance_coefficients(np.array([1.0, 0.5, 0.25])))


def test_round_trip_of_random_dark_and_bright_colours():
    rng = np.random.default_rng(10)
    rgb = np.concatenate([rng.random((200, 3)), rng.random((100, 3)) ** 6, 1.0 - rng.random((100, 3)) ** 6])
    coefficients = reflectance_coefficients(rgb)
    assert np.all(np.isfinite(coefficients))
    back = _reflectance_to_rgb(coefficients)
    assert np.abs(back - rgb * white_rgb()).max() < 1e-5
