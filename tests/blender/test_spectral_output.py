"""The multispectral EXR: what Prism writes is what colour-science's Fichet et al. 2021 reader reads
(bands, values, emissive layout), from render.py --spectral-output and from F12 with the scene's
Spectral Output on; wrong options are refused before anything renders."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.batch import run_batch
from helpers.bpy_scenes import add_camera, add_plane, add_point_light, render_linear_rgb
from helpers.colour_exr import read_with_colour


def _lamp_scene():
    add_plane("Floor", 6.0, color=(0.7, 0.7, 0.7))
    lamp = add_point_light("Lamp", 200.0, (0.0, 0.0, 2.0))
    lamp.data.prism.color_source = "ILLUMINANT"
    lamp.data.prism.illuminant = "FL11"
    add_camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), resolution=(10, 6))


def test_spectral_exr_round_trips_through_colour_sciences_reader(prism_addon, tmp_path):
    spectral_exr = importlib.import_module(f"{prism_addon.__name__}.engine.output.spectral_exr")
    rng = np.random.default_rng(4)
    centres = np.linspace(365.0, 825.0, 47)
    bands = rng.random((5, 7, 47)) * 3.0
    rgb = rng.random((5, 7, 3))
    path = spectral_exr.write_spectral_exr(tmp_path / "bands.exr", centres, bands, rgb)
    info, wavelengths, values, preview = read_with_colour(path, tmp_path)
    assert info["emissive"] and not info["polarised"] and info["components"] == ["S0"]
    assert info["attributes"]["spectralLayoutVersion"] == "1.0"
    assert np.array_equal(wavelengths, centres)
    assert np.array_equal(values, bands.astype(np.float32)) and np.array_equal(preview, rgb.astype(np.float32))
    assert not list(tmp_path.glob(".*.tmp*"))  # written through a temporary file, then renamed


def test_render_py_writes_the_bands_prism_rendered(fresh_scene, tmp_path, capsys):
    _lamp_scene()
    fresh_scene.prism.spectral_band_nm = 20.0
    blend = tmp_path / "lamp.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    status, line = run_batch(capsys, "--samples", 16, "--output", tmp_path / "out.exr",
                             "--spectral-output", tmp_path / "bands_###.exr", "--frames", "3")
    assert status == 0, line
    info, wavelengths, values, rgb = read_with_colour(tmp_path / "bands_003.exr", tmp_path)
    assert info["emissive"] and len(wavelengths) == 24 and wavelengths[0] == pytest.approx(360 + 470 / 48)
    assert values.shape == (6, 10, 24) and np.all(values >= 0)
    # Integrated against the CIE functions, the bands give the render's own colour (FL11's peaks make
    # 20 nm bands coarse, hence the tolerance).
    from prism_spectral.engine.tracer.spectra import cie  # the add-on's copy, loaded by the batch run

    band_cmf = cie.cie_xyz_cmf(wavelengths)
    xyz = values.mean(axis=(0, 1)) @ band_cmf * (470 / 24) / cie.CMF_Y_INTEGRAL
    assert np.allclose(cie.xyz_to_linear_rec709(xyz), rgb.mean(axis=(0, 1)), rtol=0.1)


def test_f12_writes_the_scenes_spectral_output_and_sample_chunks_do_not(fresh_scene, tmp_path, capsys):
    _lamp_scene()
    fresh_scene.prism.use_spectral_output = True
    fresh_scene.prism.spectral_output_path = str(tmp_path / "f12_##.exr")
    fresh_scene.frame_current = 7
    render_linear_rgb(fresh_scene, samples=4)
    written = tmp_path / "f12_07.exr"
    info, wavelengths, values, _ = read_with_colour(written, tmp_path)
    assert info["emissive"] and len(wavelengths) == 47 and values.shape == (6, 10, 47)
    written.unlink()
    status, line = run_batch(capsys, "--chunk-seed", 0, "--samples", 2, "--output", tmp_path / "chunk.exr")
    assert status == 0 and not written.exists()  # a chunk holds some samples, not the render's spectra


@pytest.mark.parametrize("arguments, message", [
    (["--spectral-output", "bands.png"], "--spectral-output must end in .exr (got 'bands.png')"),
    (["--spectral-output", "out.exr"], "--spectral-output and --output name the same file"),
    (["--spectral-output", "b.exr", "--chunk-seed", "1", "--samples", "4"],
     "--spectral-output needs a whole render, which --chunk-seed does not make"),
])
def test_wrong_spectral_output_options_are_refused(capsys, tmp_path, bad_input, arguments, message):
    arguments = [str(tmp_path / a) if a.endswith((".exr", ".png")) else a for a in arguments]
    status, line = run_batch(capsys, "scene.blend", "--output", tmp_path / "out.exr", *arguments, in_blender=False)
    assert status == 2 and message in line.replace(str(tmp_path) + "/", "")
    bad_input("render.py scene.blend --output out.exr " + " ".join(a.replace(str(tmp_path) + "/", "") for a in arguments),
              status, line.replace(str(tmp_path) + "/", ""))


def test_gaussian_rgb_mode_refuses_spectral_output_naming_the_fix(fresh_scene, tmp_path, capsys, bad_input):
    _lamp_scene()
    fresh_scene.prism.wavelength_mode = "GAUSSIAN_RGB"
    fresh_scene.prism.use_spectral_output = True
    fresh_scene.prism.spectral_output_path = str(tmp_path / "bands.exr")
    status, line = run_batch(capsys, "--output", tmp_path / "x.png")
    assert status == 1 and "Spectral output needs CIE hero wavelengths" in line and "Render ▸ Prism" in line
    bad_input("Spectral Output on in Gaussian RGB mode", status, line)
