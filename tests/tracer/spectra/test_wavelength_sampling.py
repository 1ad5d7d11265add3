"""Compiled wavelength sampling against the reference (numpy/scipy) distributions: same wavelengths,
same densities, chi-square of the guided table, and the film's RGB of known spectra."""

import numpy as np
import pytest
from scipy import stats
from scipy.special import ndtri

from engine.tracer.scene import SpectrumSpec
from engine.tracer.settings import RenderSettings
from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelength_guide import build_guide
from engine.tracer.spectra.wavelength_sampling import (build, inverse_normal_cdf, radiance_to_rgb,
                                                       sample_wavelengths)
from engine.tracer.spectra.wavelengths import GaussianChannels, sample_visible_wavelengths
from helpers.spectral_oracles import gaussian_channel_samples_to_rgb


def _draw(ws, u):
    k = ws.count
    lam = np.empty((len(u), k))
    pdf = np.empty((len(u), k))
    for i in range(len(u)):
        sample_wavelengths(ws, u[i, 0], u[i, 1], u[i, 2], lam[i], pdf[i])
    return lam, pdf


def test_inverse_normal_cdf_matches_scipy():
    p = np.concatenate([np.linspace(1e-12, 1 - 1e-12, 2001), [1e-300, 1e-20, 0.02425, 0.97575, 0.5]])
    got = np.array([inverse_normal_cdf(x) for x in p])
    assert np.allclose(got, ndtri(p), rtol=1e-13, atol=1e-13)


def test_cie_hero_wavelengths_match_the_reference_sampler():
    ws = build(RenderSettings(wavelengths_per_path=4))
    u = np.random.default_rng(0).random((500, 3))
    lam, pdf = _draw(ws, u)
    ref_lam, ref_pdf = sample_visible_wavelengths(u[:, 0], 4)
    assert np.allclose(lam, ref_lam, rtol=1e-12) and np.allclose(pdf, ref_pdf, rtol=1e-10)


def test_gaussian_channels_match_the_reference_sampler():
    s = RenderSettings(wavelength_mode="gaussian_rgb")
    ws = build(s)
    u = np.random.default_rng(1).random((500, 3))
    lam, pdf = _draw(ws, u)
    ref = GaussianChannels(s.channel_means_nm, s.channel_sigmas_nm)
    ref_lam, ref_pdf = ref.sample(u)
    assert np.allclose(lam, ref_lam, rtol=1e-11) and np.allclose(pdf, ref_pdf, rtol=1e-9)


def test_guided_sampling_follows_its_density_chi_square():
    table = SpectrumTable()
    sid = table.emission(SpectrumSpec(kind="monochromatic", wavelength_nm=589.0, width_nm=2.0))
    ws = build(RenderSettings(wavelengths_per_path=1), build_guide(table.arrays(), [(sid, 1.0)]))
    u = np.random.default_rng(2).random((200_000, 3))
    lam, pdf = _draw(ws, u)
    edges = np.linspace(360.0, 830.0, 4701)  # 0.1 nm cells: the table's own
    observed = np.histogram(lam[:, 0], bins=edges)[0]
    # merge cells into ~100 bins of equal expected mass for the test
    cdf = ws.guided_cdf
    cuts = np.searchsorted(cdf, np.linspace(0, 1, 101)[1:-1])
    obs = np.add.reduceat(observed, np.concatenate([[0], cuts]))
    exp = np.add.reduceat(ws.guided_mass, np.concatenate([[0], cuts])) * len(u)
    keep = exp > 0
    assert stats.chisquare(obs[keep], exp[keep] * obs.sum() / exp[keep].sum()).pvalue > 1e-3
    assert np.all(np.abs(lam[:, 0] - 589.0) <= 6.0)  # nothing else emits: every sample on the line
    cell = np.clip(((lam[:, 0] - 360.0) / 0.1).astype(int), 0, 4699)
    assert np.allclose(pdf[:, 0], ws.guided_mass[cell] / 0.1)


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_film_rgb_of_a_white_emitter_is_its_colour_on_average(mode):
    s = RenderSettings(wavelength_mode=mode)
    ws = build(s)
    u = (np.arange(20000)[:, None] + 0.5) / 20000 * np.ones((1, 3))
    lam, pdf = _draw(ws, u)
    white = emission_spectrum(SpectrumSpec()).evaluate(lam)
    rgb = np.array([radiance_to_rgb(ws, white[i], lam[i], pdf[i]) for i in range(len(u))]).mean(0)
    if mode == "cie":
        ref = cie.xyz_to_linear_rec709(cie.spectral_samples_to_xyz(white, lam, pdf)).mean(0)
        assert np.allclose(rgb, ref, rtol=1e-12) and np.allclose(rgb, 1.0, atol=1e-3)
    else:
        ref = gaussian_channel_samples_to_rgb(white, lam, pdf, GaussianChannels()).mean(0)
        assert np.allclose(rgb, ref, rtol=1e-12)
