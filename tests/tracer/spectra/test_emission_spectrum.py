import numpy as np
import pytest

from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.errors import PrismInputError
from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra.wavelengths import sample_visible_wavelengths


def _estimated_xyz(spectrum, n=4096):
    wavelength_nm, pdf = sample_visible_wavelengths((np.arange(n) + 0.5) / n, 4)
    return cie.spectral_samples_to_xyz(spectrum.evaluate(wavelength_nm), wavelength_nm, pdf).mean(axis=0)


def test_default_spec_is_white():
    spectrum = emission_spectrum(SpectrumSpec())
    assert np.allclose(cie.xyz_to_linear_rec709(_estimated_xyz(spectrum)), 1.0, atol=1e-3)
    assert spectrum.support_nm == (360.0, 830.0)


@pytest.mark.parametrize("temperature_k", [1500.0, 6500.0, 20000.0])
def test_blackbody_has_white_luminance(temperature_k):
    spectrum = emission_spectrum(SpectrumSpec(kind="blackbody", temperature_k=temperature_k))
    assert _estimated_xyz(spectrum)[1] == pytest.approx(1.0, rel=2e-3)


def test_monochromatic_line():
    spectrum = emission_spectrum(SpectrumSpec(kind="monochromatic", wavelength_nm=600.0, width_nm=2.0))
    lo, hi = spectrum.support_nm
    assert lo == pytest.approx(594.0) and hi == pytest.approx(606.0)
    assert spectrum.evaluate(np.array([lo - 0.01, hi + 0.01, 500.0])).max() == 0.0
    # half maximum at +-FWHM/2
    peak = spectrum.evaluate(600.0)
    assert spectrum.evaluate(601.0) == pytest.approx(0.5 * peak, rel=1e-9)
    # luminance 1, importance-sampled uniformly over the support
    n = 20000
    wl = lo + (hi - lo) * (np.arange(n) + 0.5) / n
    y = np.mean(spectrum.evaluate(wl) * cie.cie_xyz_cmf(wl)[:, 1]) * (hi - lo) / cie.CMF_Y_INTEGRAL
    assert y == pytest.approx(1.0, rel=1e-4)
    rgb = cie.xyz_to_linear_rec709(np.mean(spectrum.evaluate(wl)[:, None] * cie.cie_xyz_cmf(wl), axis=0))
    assert np.argmax(rgb) == 0  # orange-red


def test_line_support_is_clipped_to_the_visible_range():
    spectrum = emission_spectrum(SpectrumSpec(kind="monochromatic", wavelength_nm=365.0, width_nm=10.0))
    assert spectrum.support_nm == (360.0, 395.0)


@pytest.mark.parametrize(
    "spec, message",
    [
        (SpectrumSpec(kind="monochromatic", wavelength_nm=200.0), "outside 360"),
        (SpectrumSpec(kind="monochromatic", wavelength_nm=np.nan), "outside 360"),
        (SpectrumSpec(kind="monochromatic", width_nm=0.0), "width"),
        (SpectrumSpec(kind="monochromatic", width_nm=np.nan), "width"),
        (SpectrumSpec(kind="blackbody", temperature_k=500.0), "500 K is outside 1000–40000 K"),
        (SpectrumSpec(kind="rgb", rgb=(np.nan, 1.0, 1.0)), "NaN"),
        (SpectrumSpec(kind="laser"), "Unknown emission spectrum kind"),
    ],
)
def test_bad_specs_raise(spec, message):
    with pytest.raises(PrismInputError, match=message):
        emission_spectrum(spec)


@pytest.mark.parametrize("centre, width", [(600.0, 2.0), (365.0, 10.0), (550.0, 0.05)])
def test_monochromatic_line_importance_sampling(centre, width):
    from scipy import integrate, stats

    spectrum = emission_spectrum(SpectrumSpec(kind="monochromatic", wavelength_nm=centre, width_nm=width))
    lo, hi = spectrum.support_nm
    assert integrate.quad(spectrum.pdf, lo, hi, points=[centre])[0] == pytest.approx(1.0, abs=1e-8)
    n = 20000
    wl, pdf = spectrum.sample_wavelengths(np.random.default_rng(8).random(n))
    assert np.all((wl >= lo) & (wl <= hi)) and np.allclose(pdf, spectrum.pdf(wl))
    # the line is proportional to its pdf: the weight is constant
    weight = spectrum.evaluate(wl) / pdf
    assert np.allclose(weight, weight[0], rtol=1e-9)
    edges = np.linspace(lo, hi, 31)
    expected = np.array([integrate.quad(spectrum.pdf, a, b)[0] for a, b in zip(edges[:-1], edges[1:])]) * n
    keep = expected > 5
    observed, _ = np.histogram(wl, edges)
    obs = np.append(observed[keep], observed[~keep].sum())
    exp = np.append(expected[keep], expected[~keep].sum())
    if exp[-1] == 0:
        obs, exp = obs[:-1], exp[:-1]
    assert stats.chisquare(obs, exp * obs.sum() / exp.sum()).pvalue > 1e-3
    # the luminance-1 normalisation, estimated with this sampler
    y = np.mean(weight * cie.cie_xyz_cmf(wl)[:, 1]) / cie.CMF_Y_INTEGRAL
    assert y == pytest.approx(1.0, rel=1e-3)
