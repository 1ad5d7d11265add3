"""Blender 4.4+'s own light Temperature (Light ▸ Temperature checkbox), as Cycles renders it: the light's Color
× the colour of a blackbody at that temperature (luminance 1), at the light's power.

Prism renders it as a spectrum: Planck's law at the temperature, scaled to luminance 1, filtered by the Color as
a reflectance of that colour would filter it (``spectra.tinted_blackbody``). In white that is exactly Colour
Source ▸ Blackbody, and it renders Cycles' RGB per channel within 0.1 % (measured; the test allows 1 %). A
saturated Color differs from Cycles' per-channel product, as a spectral filter differs from an RGB multiply:
the test holds it to the closed form of the filtered spectrum instead.

Before: the checkbox was warned and ignored, and a 3200 K light rendered white: (0.595, 1.155, 3.067) × Cycles.
"""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light
from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world

SAMPLES = 16
TINT = (1.0, 0.5, 0.2)


def _lit_floor():
    """A grey Lambertian floor under a point light 1 m up, seen from 3 m above: one bounce."""
    add_plane("Floor", 4.0, color=(0.8, 0.8, 0.8), specular=0.0)
    light = add_point_light("Bulb", 100.0, (0.0, 0.0, 1.0)).data
    add_camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), lens_mm=80.0)
    bpy.context.scene.world = black_world()
    bpy.context.scene.prism.max_bounces = 1
    light.use_temperature = True
    return light


def _mean_rgb(image):
    return image[..., :3].reshape(-1, 3).mean(axis=0)


@pytest.mark.parametrize("temperature_k", [3200.0, 9000.0])
def test_a_white_light_at_a_temperature_renders_cycles_rgb(fresh_scene, temperature_k):
    light = _lit_floor()
    light.temperature = temperature_k
    cycles = _mean_rgb(render_cycles_rgba(fresh_scene, SAMPLES, 0, max_bounces=1))
    prism = _mean_rgb(render_prism_rgba(fresh_scene, SAMPLES, 0))
    print(f"MEASURED {temperature_k:g} K: Prism {prism}, Cycles {cycles}, ratio {prism / cycles}")
    assert np.allclose(prism, cycles, rtol=0.01), (prism, cycles)


def test_in_white_it_is_colour_source_blackbody(prism_addon, fresh_scene):
    lights = importlib.import_module(f"{prism_addon.__name__}.engine.export.lights")
    light = _lit_floor()
    light.temperature = 4100.0
    blender = lights.light_spectrum("Bulb", light)
    light.use_temperature = False
    light.prism.color_source, light.prism.temperature_k = "BLACKBODY", 4100.0
    assert blender == lights.light_spectrum("Bulb", light)


def _rec709_of(spectrum):
    """Rec.709 RGB of a spectrum on the 1 nm grid 360-830 nm, through colour-science's CIE 1931 observer."""
    import colour

    shape = colour.SpectralShape(360, 830, 1)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape).values
    matrix = colour.RGB_COLOURSPACES["ITU-R BT.709"].matrix_XYZ_to_RGB
    return matrix @ (spectrum @ cmfs)


def test_a_coloured_light_filters_plancks_spectrum(prism_addon, fresh_scene):
    """Color (1, 0.5, 0.2) at 3200 K: the image's RGB over the white light's is the filtered spectrum's RGB
    over Planck's (closed form through colour-science), per channel within 1 %."""
    import colour

    tinted = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.spectra.tinted_blackbody")
    light = _lit_floor()
    light.temperature = 3200.0
    white = _mean_rgb(render_prism_rgba(fresh_scene, SAMPLES, 0))
    light.color = TINT
    coloured = _mean_rgb(render_prism_rgba(fresh_scene, SAMPLES, 0))
    cycles = _mean_rgb(render_cycles_rgba(fresh_scene, SAMPLES, 0, max_bounces=1))
    planck = colour.sd_blackbody(3200.0, colour.SpectralShape(360, 830, 1)).values
    expected = _rec709_of(planck * tinted.reflectance_on_grid(TINT)) / _rec709_of(planck)
    print(f"MEASURED tinted / white: Prism {coloured / white}, closed form {expected}; "
          f"Prism {coloured} against Cycles' RGB product {cycles} ({coloured / cycles})")
    assert np.allclose(coloured / white, expected, rtol=0.01), (coloured / white, expected)
    assert coloured[0] > coloured[1] > coloured[2] > 0.0


def test_settings_prism_does_not_render_as_cycles_are_named(prism_addon, fresh_scene):
    """Colour Source other than RGB wins over Blender's Temperature; below 1000 K renders at 1000 K."""
    light = _lit_floor()
    warnings = []
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    light.prism.color_source = "ILLUMINANT"
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert any("Blender's Temperature (6500 K) is not used" in w and "Illuminant" in w for w in warnings), warnings

    light.prism.color_source, light.temperature = "RGB", 900.0
    warnings.clear()
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert any("Temperature 900 K is below" in w and "rendered at 1000 K" in w for w in warnings), warnings
    assert scene.lights[0].spectrum.temperature_k == 1000.0
