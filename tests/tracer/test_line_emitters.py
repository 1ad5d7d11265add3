"""A line emitter end to end: wavelength sampling guided toward the line renders its colour."""

import numpy as np

from engine.tracer.spectra import cie
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.renderer import Renderer
from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra.trapezoid import trapezoid

from .test_renderer import _closed_form
from .tracer_scenes import plane_under_point_light, settings


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
    xyz = trapezoid(line.evaluate(grid)[:, None] * cie.cie_xyz_cmf(grid), grid, axis=0) / cie.CMF_Y_INTEGRAL
    rgb = cie.xyz_to_linear_rec709(xyz)
    expected = _closed_form(scene, power, albedo, height).mean() * rgb
    got = r.image_rgb().astype(np.float64).mean((0, 1))
    assert np.allclose(got, expected, rtol=0.02, atol=0.002 * np.abs(expected).max())
    assert r.stats["nan_samples"] == 0
