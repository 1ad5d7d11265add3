"""Measured spectra in Blender: a light's or material's illuminant, spectrum file or colour-checker
patch becomes the tracer spectrum the render uses; a wrong one is refused with one message naming the
object, the setting and the fix (in Blender and in render.py)."""

from __future__ import annotations

import importlib

import bpy
import pytest

from helpers.batch import run_batch
from helpers.bpy_scenes import add_camera, add_plane, add_point_light


def _scene():
    add_plane("Floor", 4.0)
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    add_camera((0.0, -3.0, 1.5), (1.1, 0.0, 0.0), resolution=(8, 8))
    return bpy.data.lights["Bulb"].prism, bpy.data.materials["Floor material"]


def _export(prism_addon):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get())


def test_light_and_material_spectra_reach_the_tracer(prism_addon, fresh_scene, tmp_path):
    light, material = _scene()
    (tmp_path / "lamp.csv").write_text("wavelength_nm,value\n400,1\n550,3\n700,2\n")
    bpy.ops.wm.save_as_mainfile(filepath=str(tmp_path / "scene.blend"))
    light.color_source, light.illuminant = "ILLUMINANT", "led-b3"
    material.prism.reflectance_source = "MEASURED"
    material.prism.measured_reflectance = "ColorChecker N Ohta: moderate red"
    material.prism.emission_source, material.prism.emission_illuminant = "ILLUMINANT", "HP1"
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Emission Color"].default_value = (0.0, 0.0, 0.0, 1.0)  # the illuminant decides the colour
    node.inputs["Emission Strength"].default_value = 2.0
    scene = _export(prism_addon)
    assert (scene.lights[0].spectrum.kind, scene.lights[0].spectrum.illuminant) == ("illuminant", "LED-B3")
    floor = scene.materials[0]
    assert (floor.reflectance.kind, floor.reflectance.name) == ("measured", "ColorChecker N Ohta: moderate red")
    assert floor.emission.illuminant == "HP1" and floor.emission_strength == 2.0

    light.color_source, light.spectrum_file = "FILE", "//lamp.csv"  # relative to the .blend file
    material.prism.reflectance_source, material.prism.reflectance_file = "FILE", str(tmp_path / "lamp.csv")
    (tmp_path / "lamp.csv").write_text("400,0.1\n550,0.3\n700,0.2\n")
    scene = _export(prism_addon)
    assert scene.lights[0].spectrum.table.values == (0.1, 0.3, 0.2)
    assert scene.lights[0].spectrum.table.source == str(tmp_path / "lamp.csv")
    assert scene.materials[0].reflectance.table.wavelength_nm == (400.0, 550.0, 700.0)


def _light(**values):
    def mutate(tmp_path):
        settings = bpy.data.lights["Bulb"].prism
        for key, value in values.items():
            setattr(settings, key, value.format(tmp=tmp_path) if isinstance(value, str) else value)

    return mutate


def _material(**values):
    def mutate(tmp_path):
        settings = bpy.data.materials["Floor material"].prism
        for key, value in values.items():
            setattr(settings, key, value.format(tmp=tmp_path) if isinstance(value, str) else value)
        node = bpy.data.materials["Floor material"].node_tree.nodes["Principled BSDF"]
        node.inputs["Emission Strength"].default_value = 1.0

    return mutate


def _file(name, text):
    def write(tmp_path):
        (tmp_path / name).write_text(text)

    return write


CASES = {
    "unknown illuminant": (
        None, _light(color_source="ILLUMINANT", illuminant="FL13"),
        "Light 'Bulb': Light ▸ Prism ▸ Illuminant: 'FL13' is not one of colour-science's standard illuminants; "
        "did you mean 'FL3', 'FL1', 'FL3.13'?",
    ),
    "no spectrum file chosen": (
        None, _light(color_source="FILE", spectrum_file=""),
        "Light 'Bulb': no spectrum file is chosen; set Light ▸ Prism ▸ Spectrum File.",
    ),
    "missing spectrum file": (
        None, _light(color_source="FILE", spectrum_file="{tmp}/lamp.csv"),
        "Light 'Bulb' (Light ▸ Prism): spectrum file '{tmp}/lamp.csv' does not exist",
    ),
    "spectrum file that is not a spectrum": (
        _file("notes.txt", "shopping list\nmilk, eggs\n"), _light(color_source="FILE", spectrum_file="{tmp}/notes.txt"),
        "Light 'Bulb' (Light ▸ Prism): spectrum file '{tmp}/notes.txt': row 2 ('milk, eggs') is not "
        "numbers, so this is not a spectrum",
    ),
    "spectrum file in micrometres": (
        _file("um.csv", "0.40,1\n0.55,2\n0.70,1\n"), _light(color_source="FILE", spectrum_file="{tmp}/um.csv"),
        "has wavelengths 0.4-0.7, outside 100-3000 nm: the first column must be the wavelength in nanometres",
    ),
    "negative emission file": (
        _file("neg.csv", "400,1\n500,-0.2\n600,1\n"),
        _material(emission_source="FILE", emission_file="{tmp}/neg.csv"),
        "Material 'Floor material' (Material ▸ Prism ▸ Emission): spectrum file '{tmp}/neg.csv' is negative "
        "(-0.2 at 500 nm)",
    ),
    "reflectance file in percent": (
        _file("pct.csv", "400,12\n500,48\n600,80\n"),
        _material(reflectance_source="FILE", reflectance_file="{tmp}/pct.csv"),
        "reaches 80 at 600 nm (3 of 3 values above 1): a reflectance lies within 0-1, and these values look "
        "like percent: divide them by 100.",
    ),
    "reflectance file just above 1 (1.0001)": (
        _file("over.csv", "400,0.2\n500,1.0001\n600,0.9\n"),
        _material(reflectance_source="FILE", reflectance_file="{tmp}/over.csv"),
        "reflectance file '{tmp}/over.csv' reaches 1.0001 at 500 nm (1 of 3 values above 1): a reflectance lies "
        "within 0-1 (a surface cannot reflect more light than reaches it), so this is not a reflectance: check the "
        "file's second column, or clip it to 1.",
    ),
    "reflectance file at 1.2": (
        _file("bright.csv", "400,1.2\n500,1.1\n600,0.9\n"),
        _material(reflectance_source="FILE", reflectance_file="{tmp}/bright.csv"),
        "reaches 1.2 at 400 nm (2 of 3 values above 1): a reflectance lies within 0-1 (a surface cannot reflect",
    ),
    "spectrum file saved as UTF-16": (
        lambda tmp_path: (tmp_path / "u16.csv").write_bytes("400,1\n500,2\n600,1\n".encode("utf-16")),
        _light(color_source="FILE", spectrum_file="{tmp}/u16.csv"),
        "spectrum file '{tmp}/u16.csv' is UTF-16 (little-endian) text, which Prism does not read: save it as "
        "UTF-8 (e.g. Notepad ▸ Save As ▸ Encoding UTF-8).",
    ),
    "unknown colour-checker patch": (
        None, _material(reflectance_source="MEASURED", measured_reflectance="ColorChecker N Ohta: dark skn"),
        "Material 'Floor material': Material ▸ Prism ▸ Base Colour ▸ Measured Reflectance: "
        "'ColorChecker N Ohta: dark skn' is not a colour-checker patch colour-science knows; did you mean "
        "'ColorChecker N Ohta: dark skin'",
    ),
    "emission illuminant stored empty": (
        None, _material(emission_source="ILLUMINANT", emission_illuminant=""),
        "Material 'Floor material': Material ▸ Prism ▸ Emission ▸ Illuminant: '' is not one of colour-science's",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_spectra_name_the_object_setting_and_fix(prism_addon, fresh_scene, tmp_path, capsys, bad_input, case):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    prepare, mutate, message = CASES[case]
    _scene()
    if prepare:
        prepare(tmp_path)
    mutate(tmp_path)
    message = message.format(tmp=tmp_path)
    with pytest.raises(export.PrismInputError) as exported:
        _export(prism_addon)
    assert message in str(exported.value)
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert (status, line) == (1, f"Prism: error: {exported.value}")
    bad_input(case, status, line)
