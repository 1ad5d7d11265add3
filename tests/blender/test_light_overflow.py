"""Light values float32 cannot carry: emission strengths, light powers, HDRI texels and spectrum files
near float32's or float64's limits are refused at export naming the object, the setting and the value
(never a frame of 3.4e38 or a silent black one, never a numpy RuntimeWarning); NaN, infinite and negative
HDRI texels are rendered as 0 with a warning that counts them and says how much light that adds.
"""

from __future__ import annotations

import importlib
import warnings as python_warnings

import bpy
import numpy as np
import pytest

from helpers.batch_outcome import batch_refusal, batch_warning
from helpers.bpy_worlds import blender_image, environment_world
from helpers.error_scenes import base_scene, light


def _export(addon):
    found = []
    export = importlib.import_module(f"{addon.__name__}.engine.export")
    with python_warnings.catch_warnings():
        python_warnings.simplefilter("error", RuntimeWarning)  # numpy's overflow warnings must not leak
        scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), found)
    return scene, found


def _export_error(addon) -> str:
    errors = importlib.import_module(f"{addon.__name__}.engine.tracer.errors")
    with pytest.raises(errors.PrismInputError) as caught:
        _export(addon)
    return str(caught.value)


def _emission_strength(value):
    node = bpy.data.materials["Floor material"].node_tree.nodes["Principled BSDF"]
    node.inputs["Emission Strength"].default_value = value


def _spectrum_file(tmp_path, value):
    path = tmp_path / "lamp.csv"
    path.write_text("".join(f"{nm}, {value!r}\n" for nm in range(380, 790, 10)))
    light(color_source="FILE", spectrum_file=str(path))()


@pytest.mark.parametrize("description, mutate, expected", [
    ("Principled Emission Strength 1e38", lambda tmp: _emission_strength(1e38),
     "Material 'Floor material', Principled BSDF 'Principled BSDF': Emission Strength × Emission Color is 1e+38; "
     "Prism renders light values up to 1e+20 (float32 overflows beyond, a white or black frame): lower it."),
    ("light Power 1e38 W", lambda tmp: light(energy=1e38)(),
     "Light 'Bulb': Power is 1e+38 W; Prism renders light values up to 1e+20 (float32 overflows beyond, a white or "
     "black frame): lower it."),
    ("light Power 1e-40 W (a float32 denormal)", lambda tmp: light(energy=1e-40)(),
     "Light 'Bulb': Power is 1e-40 W, below 1e-30, which float32 renders as 0 (a black light that looks on): set it "
     "to 0 for no light, or to 1e-30 or more."),
    ("light spectrum file of values 1e308", lambda tmp: _spectrum_file(tmp, 1e308),
     "spectrum file '{path}' peaks at 1e+308; Prism reads emission spectra peaking within 1e-30 to 1e+20: rescale "
     "the file (only its shape counts, the strength sets the brightness)."),
    ("light spectrum file of values 1e-320", lambda tmp: _spectrum_file(tmp, 1e-320),
     "spectrum file '{path}' peaks at 1e-320; Prism reads emission spectra peaking within 1e-30 to 1e+20: "
     "rescale the file (only its shape counts, the strength sets the brightness)."),
])
def test_light_values_beyond_float32_are_refused(prism_addon, fresh_scene, tmp_path, bad_input, capsys, description,
                                                 mutate, expected):
    base_scene()
    mutate(tmp_path)
    message = _export_error(prism_addon)
    assert message.endswith(expected.format(path=tmp_path / "lamp.csv"))
    bad_input(description, *batch_refusal(capsys, tmp_path, message))


def test_an_hdri_texel_near_float32s_limit_is_refused(prism_addon, fresh_scene, bad_input, capsys, tmp_path):
    base_scene()
    texels = np.full((4, 8, 3), 0.5, np.float32)
    texels[1, 2] = 1e38
    environment_world(blender_image("hot", texels))
    message = _export_error(prism_addon)
    assert message.startswith("World 'HDRI', Environment Texture 'Environment Texture': the brightest texel of image "
                              "'hot' × the Background's Strength is 1e+38; Prism renders light values up to 1e+20")
    bad_input("HDRI with a texel of 1e38", *batch_refusal(capsys, tmp_path, message))


def test_nan_infinite_and_negative_hdri_texels_are_counted_and_their_light_told(prism_addon, fresh_scene, bad_input,
                                                                               capsys, tmp_path):
    base_scene()
    texels = np.full((4, 8, 3), 1.0, np.float32)
    texels[0, 0] = np.nan
    texels[0, 1] = (np.inf, 1.0, 1.0)  # what Blender's float32 pixels hold for 1e308
    texels[2, :4] = -0.5  # four texels of the row below the horizon, grey -0.5
    environment_world(blender_image("bad", texels))
    scene, found = _export(prism_addon)
    assert np.isfinite(scene.world.image_rgb).all() and scene.world.image_rgb.min() == 0.0
    # The light the negative texels hold, by solid angle (sin of the polar angle per row), against the rest:
    weights = np.sin((np.arange(4) + 0.5) / 4 * np.pi)
    positive = weights.sum() * 8 - weights[0] * 2 - weights[2] * 4  # rows of 8 white texels, less the zeroed ones
    negative = weights[2] * 4 * 0.5
    taken, more = 100 * negative / positive, 100 * negative / (positive - negative)
    expected = (f"World 'HDRI', Environment Texture 'Environment Texture': image 'bad' has 1 NaN, 1 infinite and 4 "
                "negative texels (of 32); Prism renders NaN and infinite texels black and negative values as 0. "
                f"The negative values would take {taken:.2g} % of the "
                f"image's light away (Cycles subtracts it): Prism's world emits {more:.2g} % more. Clamp the image at "
                "0 and replace its NaN and infinite texels to match Cycles.")
    assert expected in found
    bad_input("HDRI with NaN, infinite and negative texels", *batch_warning(capsys, tmp_path, expected))
