"""The multispectral film: bands tile 360-830 nm, each pixel's band radiance is the emitted spectrum's
band mean times the closed-form irradiance, integrates back to the RGB image, and does not depend on
the thread count."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.renderer import Renderer
from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.spectral_film import band_edges_nm
from engine.tracer.spectra.trapezoid import trapezoid

from .test_renderer import _closed_form
from .tracer_scenes import plane_under_point_light, settings


def test_bands_tile_the_visible_range():
    assert len(band_edges_nm(10.0)) == 48 and band_edges_nm(10.0)[[0, -1]].tolist() == [360.0, 830.0]
    assert np.diff(band_edges_nm(20.0)) == pytest.approx(470.0 / 24)
    with pytest.raises(PrismInputError, match="band width 0.5 nm is outside 1-100 nm"):
        band_edges_nm(0.5)
    with pytest.raises(PrismInputError, match="Spectral output needs CIE hero wavelengths"):
        settings(spectral_band_nm=10.0, wavelength_mode="gaussian_rgb").validate()


def _lamp_scene(spec):
    scene = plane_under_point_light(size=16, power=100.0, height=2.0, albedo=1.0)
    scene.lights[0].spectrum = spec
    return scene


def test_band_radiance_is_the_emitted_spectrum_times_the_irradiance():
    spec = SpectrumSpec(kind="illuminant", illuminant="FL2")
    scene = _lamp_scene(spec)
    with Renderer(scene, settings(samples=64, samples_per_pass=64, spectral_band_nm=10.0)) as renderer:
        renderer.render_pass()
        film = renderer.spectral_film
        bands = film.mean().mean(axis=(0, 1))
    assert film.bands == 47 and film.centres_nm[0] == 365.0
    fine = np.linspace(360.0, 830.0, 47 * 200 + 1)
    emitted = emission_spectrum(spec).evaluate(fine)
    band_means = np.array([trapezoid(emitted[200 * b: 200 * b + 201], fine[200 * b: 200 * b + 201]) / 10.0
                           for b in range(47)])
    expected = _closed_form(scene, 100.0, 1.0, 2.0).mean() * band_means
    assert np.abs(bands - expected).max() < 0.03 * expected.max()
    assert np.abs(bands - expected).sum() < 0.02 * expected.sum()


def test_bands_integrate_back_to_the_rgb_image_and_ignore_the_thread_count():
    scene = _lamp_scene(SpectrumSpec(kind="illuminant", illuminant="HP1"))
    results = []
    for threads in (1, 2):
        with Renderer(scene, settings(samples=8, samples_per_pass=8, threads=threads, spectral_band_nm=1.0)) as r:
            r.render_pass()
            results.append((r.spectral_film.mean(), r.image_rgb().astype(np.float64), r.spectral_film.centres_nm))
    assert np.array_equal(results[0][0], results[1][0])
    bands, rgb, centres = results[0]
    xyz = bands @ cie.cie_xyz_cmf(centres) / cie.CMF_Y_INTEGRAL  # 1 nm bands: the integral itself
    # Equal up to where in its nanometre each sample fell (the CMFs are taken at band centres).
    assert np.allclose(cie.xyz_to_linear_rec709(xyz), rgb, rtol=1e-2, atol=1e-3 * rgb.max())


def test_no_spectral_buffer_unless_asked():
    with Renderer(_lamp_scene(SpectrumSpec()), settings()) as renderer:
        assert renderer.spectral_film is None
