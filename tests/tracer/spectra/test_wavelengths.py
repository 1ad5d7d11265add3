import numpy as np
import pytest
from scipy import integrate, stats

from engine.tracer.errors import PrismInputError
from engine.tracer.spectra.wavelengths import (
    VISIBLE_MAX_NM,
    VISIBLE_MIN_NM,
    GaussianChannels,
    sample_visible_wavelengths,
    visible_wavelength_pdf,
)

EDGES_NM = np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, 48)


def _expected_counts(pdf_fn, total):
    mass = np.array([integrate.quad(pdf_fn, a, b)[0] for a, b in zip(EDGES_NM[:-1], EDGES_NM[1:])])
    assert mass.sum() == pytest.approx(1.0, abs=1e-8)
    return mass * total


def test_visible_pdf_is_normalised_and_zero_outside():
    assert integrate.quad(visible_wavelength_pdf, VISIBLE_MIN_NM, VISIBLE_MAX_NM)[0] == pytest.approx(1.0, abs=1e-10)
    assert np.all(visible_wavelength_pdf([300.0, 359.9, 830.1, 1000.0, np.nan]) == 0.0)
    # the stated shape: 0.0072 / cosh^2(0.0072 (lambda - 538)) up to a constant
    wl = np.array([400.0, 538.0, 700.0])
    ratio = visible_wavelength_pdf(wl) * np.cosh(0.0072 * (wl - 538.0)) ** 2
    assert np.allclose(ratio, ratio[0], rtol=1e-12)


def test_stratified_wavelengths_follow_the_pdf():
    """Each column follows the density restricted to its stratum; a uniformly chosen column (the
    hero) follows the whole density."""
    rng = np.random.default_rng(1)
    n = 20000
    wavelength_nm, pdf = sample_visible_wavelengths(rng.random(n), 4)
    assert wavelength_nm.shape == pdf.shape == (n, 4)
    assert np.allclose(pdf, visible_wavelength_pdf(wavelength_nm))
    hero = wavelength_nm[np.arange(n), rng.integers(0, 4, n)]
    observed, _ = np.histogram(hero, EDGES_NM)
    assert stats.chisquare(observed, _expected_counts(visible_wavelength_pdf, n)).pvalue > 1e-3
    def cdf(wl):  # the closed form: tanh(a (lambda - c)), normalised over 360-830 nm
        lo, hi = np.tanh(0.0072 * (np.array([VISIBLE_MIN_NM, VISIBLE_MAX_NM]) - 538.0))
        return (np.tanh(0.0072 * (wl - 538.0)) - lo) / (hi - lo)

    for column in range(4):  # column j stays in the j-th quarter of the distribution
        quantile = cdf(wavelength_nm[:, column])
        assert np.all((quantile >= column / 4 - 1e-9) & (quantile <= (column + 1) / 4 + 1e-9)), column


def test_columns_are_the_strata_of_one_number():
    wavelength_nm, _ = sample_visible_wavelengths(np.array([0.1, 0.9]), 4)
    # u = 0.1 -> 0.025, 0.275, 0.525, 0.775: one point in each quarter of the distribution
    assert np.all(np.diff(wavelength_nm[0]) > 0) and np.all(np.diff(wavelength_nm[1]) > 0)
    assert np.all(wavelength_nm[0] < wavelength_nm[1])


def test_wavelength_sampling_rejects_bad_input():
    with pytest.raises(PrismInputError):
        sample_visible_wavelengths(np.array([0.5]), 0)
    with pytest.raises(PrismInputError):
        sample_visible_wavelengths(np.array([0.5, np.nan]), 4)
    with pytest.raises(PrismInputError):
        sample_visible_wavelengths(np.array([1.5]), 4)


@pytest.mark.parametrize(
    "means, sigmas",
    [((600.0, 550.0, 450.0), (25.0, 25.0, 15.0)), ((370.0, 820.0, 600.0), (40.0, 30.0, 200.0))],
)
def test_gaussian_channels_follow_their_truncated_pdf(means, sigmas):
    channels = GaussianChannels(means, sigmas)
    rng = np.random.default_rng(2)
    n = 20000
    wavelength_nm, pdf = channels.sample(rng.random((n, 3)))
    assert wavelength_nm.shape == pdf.shape == (n, 3)
    assert np.all((wavelength_nm >= VISIBLE_MIN_NM) & (wavelength_nm <= VISIBLE_MAX_NM))
    for c in range(3):

        def channel_pdf(x, c=c):
            wl = np.full(3, x)
            return channels.pdf(wl)[c]

        expected = _expected_counts(channel_pdf, n)
        keep = expected > 5  # chi-square needs populated bins; fold the tails together
        observed, _ = np.histogram(wavelength_nm[:, c], EDGES_NM)
        obs = np.append(observed[keep], observed[~keep].sum())
        exp = np.append(expected[keep], expected[~keep].sum())
        if exp[-1] == 0:
            obs, exp = obs[:-1], exp[:-1]
        exp *= obs.sum() / exp.sum()
        assert stats.chisquare(obs, exp).pvalue > 1e-3, c


def test_gaussian_channels_validation():
    with pytest.raises(PrismInputError, match="sigma"):
        GaussianChannels(sigmas_nm=(25.0, 0.0, 15.0))
    with pytest.raises(PrismInputError, match="mean"):
        GaussianChannels(means_nm=(600.0, np.nan, 450.0))
    with pytest.raises(PrismInputError, match="mean"):
        GaussianChannels(means_nm=(1000.0, 550.0, 450.0))
    with pytest.raises(PrismInputError):
        GaussianChannels().sample(np.zeros((4, 2)))


def test_matches_pbrt_v4_published_constants():
    """pbrt-v4 SampleVisibleWavelengths / VisibleWavelengthsPDF, constants as published (8 digits)."""
    u = np.array([0.0, 0.1, 0.5, 0.9, 0.999])
    wavelength_nm, pdf = sample_visible_wavelengths(u, 1)
    expected = 538.0 - 138.888889 * np.arctanh(0.85691062 - 1.82750197 * u)
    assert np.allclose(wavelength_nm[:, 0], expected, atol=2e-4)
    assert np.allclose(pdf[:, 0], 0.0039398042 / np.cosh(0.0072 * (expected - 538.0)) ** 2, rtol=1e-4)
