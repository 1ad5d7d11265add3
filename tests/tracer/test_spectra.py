"""Scene spectra: guided wavelength sampling for monochromatic emitters, per-chunk caching."""

import numpy as np
from scipy import stats

from engine.tracer import path_spectra as spectra
from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.renderer import Renderer
from engine.tracer.scene import SpectrumSpec

from .test_renderer import _closed_form
from .tracer_scenes import plane_under_point_light, settings


def test_guided_sampler_matches_its_pdf_and_covers_the_line():
    line = emission_spectrum(SpectrumSpec(kind="monochromatic", wavelength_nm=589.0, width_nm=2.0))
    g = spectra.GuidedVisibleWavelengths([line])
    u = np.random.default_rng(0).random(200_000)
    lam, pdf = g.sample(u, 4)
    assert lam.min() >= 360 and lam.max() <= 830
    near = np.abs(lam - 589.0) < 3.0
    assert 0.45 < near.mean() < 0.55  # half the samples go to the line
    # pdf consistency: histogram on the cells against the tabulated masses (coarse bins)
    edges = np.linspace(360, 830, 48)
    counts, _ = np.histogram(lam[:, 1], edges)
    cdf = np.interp(edges, g.edges, g.cdf)
    expected = np.diff(cdf) * len(lam)
    assert stats.chisquare(counts, expected).pvalue > 1e-3
    cell = np.clip(((lam - 360.0) / 0.1).astype(int), 0, len(g.mass) - 1)
    assert np.allclose(pdf, g.mass[cell] / 0.1)


def test_sodium_lamp_renders_its_colour_with_guided_wavelengths():
    power, albedo, height = 100.0, 0.5, 2.0
    scene = plane_under_point_light(size=16, power=power, height=height, albedo=albedo)
    spec = SpectrumSpec(kind="monochromatic", wavelength_nm=589.0, width_nm=2.0)
    scene.lights[0].spectrum = spec
    r = Renderer(scene, settings(samples=16, samples_per_pass=16))
    assert "guided by 1 emission line" in r.strategy
    r.render_pass()
    line = emission_spectrum(spec)
    grid = np.linspace(580, 598, 2001)
    xyz = np.trapz(line.evaluate(grid)[:, None] * cie.cie_xyz_cmf(grid), grid, axis=0) / cie.CMF_Y_INTEGRAL
    rgb = cie.xyz_to_linear_rec709(xyz)
    expected = _closed_form(scene, power, albedo, height).mean() * rgb
    got = r.image_rgb().astype(np.float64).mean((0, 1))
    assert np.allclose(got, expected, rtol=0.02, atol=0.002 * np.abs(expected).max())
    assert r.stats["nan_samples"] == 0


def test_path_wavelengths_cache_spectra_per_chunk():
    calls = []

    def spectrum(lam):
        calls.append(np.shape(lam))
        return np.asarray(lam) * 2.0

    lam = spectra.PathWavelengths(np.arange(12.0).reshape(6, 2))
    sub = lam[np.array([True, False, True, False, True, True])][np.array([1, 3])]
    assert np.array_equal(spectra.cached("k", spectrum, sub), [[8.0, 10.0], [20.0, 22.0]])
    assert np.array_equal(spectra.cached("k", spectrum, lam[np.array([5])]), [[20.0, 22.0]])
    assert calls == [(6, 2)]  # evaluated once, on the whole chunk
    plain = lam[np.arange(6), np.zeros(6, int)]
    assert type(plain) is np.ndarray and np.array_equal(plain, [0, 2, 4, 6, 8, 10])
    assert np.array_equal(spectra.cached("j", spectrum, np.ones((2, 2))), 2 * np.ones((2, 2)))
