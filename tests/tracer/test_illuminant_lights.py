"""Standard illuminants on lights: a white plane under an FL2 or HP1 lamp renders at the lamp's
colour-science chromaticity, as bright as a white lamp of the same power (luminance-normalised)."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra import cie

from .test_renderer import _closed_form
from .tracer_scenes import plane_under_point_light, settings


@pytest.mark.parametrize("illuminant", ["FL2", "HP1"])
def test_lamp_renders_at_its_colour_science_chromaticity(illuminant):
    colour = cie.import_colour()
    power, height = 100.0, 2.0
    scene = plane_under_point_light(size=16, power=power, height=height, albedo=1.0)
    scene.lights[0].spectrum = SpectrumSpec(kind="illuminant", illuminant=illuminant)
    with Renderer(scene, settings(samples=32, samples_per_pass=32)) as renderer:
        renderer.render_pass()
        xyz = cie.linear_rec709_to_xyz(renderer.image_rgb().astype(np.float64).mean(axis=(0, 1)))
    reference = colour.XYZ_to_xy(colour.sd_to_XYZ(colour.SDS_ILLUMINANTS[illuminant]))
    assert np.abs(xyz[:2] / xyz.sum() - reference).max() < 0.002
    assert xyz[1] == pytest.approx(_closed_form(scene, power, 1.0, height).mean(), rel=0.01)
