"""Measured reflectances and illuminants end to end: the 24 ColorChecker patches lit by D65 and by
CIE A render to the colours colour-science computes from the same spectra (ΔE2000 ≤ 1 after one
exposure scale)."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.spectra import cie
from engine.tracer.spectra.measured_reflectance import checker_patches, measured_reflectance

from .colour_checker_scene import CHECKER, chart_in_glowing_sphere, patch_means
from .tracer_scenes import settings


def _reference_lab(colour, illuminant):
    """Lab (white: the illuminant's) colour-science computes for each patch under ``illuminant``."""
    light = colour.SDS_ILLUMINANTS[illuminant]
    white = colour.XYZ_to_xy(colour.sd_to_XYZ(light) / 100.0)
    patches = colour.SDS_COLOURCHECKERS[CHECKER]
    xyz = np.array([colour.sd_to_XYZ(patches[name.split(": ")[1]], illuminant=light) / 100.0
                    for name in checker_patches(CHECKER)])
    return xyz, white


@pytest.mark.parametrize("illuminant", ["D65", "A"])
def test_colour_checker_renders_colour_sciences_colours(illuminant):
    colour = cie.import_colour()
    scene, windows = chart_in_glowing_sphere(illuminant)
    with Renderer(scene, settings(samples=16, samples_per_pass=16, max_bounces=1, seed=3)) as renderer:
        assert "guided by 1 measured spectrum" in renderer.strategy
        renderer.render_pass()
        rendered_xyz = cie.linear_rec709_to_xyz(patch_means(renderer.image_rgb().astype(np.float64), windows))
        assert renderer.stats["nan_samples"] == 0
    reference_xyz, white = _reference_lab(colour, illuminant)
    exposure = rendered_xyz[:, 1] @ reference_xyz[:, 1] / (rendered_xyz[:, 1] @ rendered_xyz[:, 1])
    assert exposure == pytest.approx(1.0, abs=0.01)  # luminance-normalised light: a white patch has Y = 1
    delta_e = colour.delta_E(colour.XYZ_to_Lab(exposure * rendered_xyz, white),
                             colour.XYZ_to_Lab(reference_xyz, white), method="CIE 2000")
    assert delta_e.max() <= 1.0, dict(zip(checker_patches(CHECKER), np.round(delta_e, 2)))
    if illuminant == "D65":  # the same check in colour-science's own sRGB
        rendered_srgb = colour.XYZ_to_sRGB(exposure * rendered_xyz)
        reference_srgb = colour.XYZ_to_sRGB(reference_xyz)
        assert np.abs(rendered_srgb - reference_srgb).max() < 0.02


def test_unknown_patch_names_the_material_and_the_nearest_patches():
    from engine.tracer.errors import PrismInputError
    from engine.tracer.scene import ReflectanceSpec

    scene, _ = chart_in_glowing_sphere("D65", patches=["ColorChecker N Ohta: dark skin"] * 23
                                       + ["ColorChecker N Ohta: dark skn"])
    scene.materials[23].reflectance = ReflectanceSpec(kind="measured", name="ColorChecker N Ohta: dark skn")
    with pytest.raises(PrismInputError, match="Material 'ColorChecker N Ohta: dark skn'.*did you mean "
                                             "'ColorChecker N Ohta: dark skin'"):
        Renderer(scene, settings())
    wavelength_nm, values = measured_reflectance("colorchecker n ohta: DARK SKIN")
    assert wavelength_nm[0] == 380.0 and 0.0 < values.min() < values.max() < 1.0
