"""Bundled lens list, the Camera panel read-outs and the command-line report."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.lens.__main__ import main
from engine.tracer.lens.catalogue import (
    LENS_DIRECTORY, bundled_lens_path, bundled_lenses, field_of_view_deg, lens_readouts,
)
from engine.tracer.lens.lens_file import load_lens

ROOT = Path(__file__).resolve().parents[3]


def test_bundled_lenses_are_id_name_path():
    entries = bundled_lenses()
    assert len(entries) >= 6
    for identifier, name, path in entries:
        assert Path(path).is_file() and Path(path).stem == identifier and name
        assert bundled_lens_path(identifier) == path
    with pytest.raises(PrismInputError, match="No bundled lens 'nope': choose one of"):
        bundled_lens_path("nope")


def test_readouts_for_the_panel():
    out = lens_readouts(LENS_DIRECTORY / "double_gauss_50mm.lens", fstop=4.0, focus_distance_m=2.0)
    assert out["Lens"] == "Double Gauss 50mm f/2"
    assert out["Focal length"] == "50.36 mm"
    assert out["f-number"].startswith("f/4.06")  # the stop scaled from the design's f/2
    assert out["Film at focus"].startswith("37.4")
    assert out["Field of view"].startswith("39.")
    wide_open = lens_readouts(LENS_DIRECTORY / "double_gauss_50mm.lens", fstop=1.4)
    assert "wider than the design's f/2" in wide_open["f-number"]
    fisheye = lens_readouts(LENS_DIRECTORY / "fisheye_10mm.lens", 4.0, 1.0)
    assert fisheye["Field of view"].startswith("image circle 26.")
    assert fisheye["Field of view"].endswith("mm, narrower than 36 mm")
    assert all(isinstance(v, str) for v in out.values())


def test_traced_field_of_view_shows_the_fisheye_distortion():
    fisheye = load_lens(LENS_DIRECTORY / "fisheye_10mm.lens")
    # 5 mm off axis: a rectilinear 10 mm lens sees 2 atan(0.5) = 53.1 degrees; this fisheye
    # follows the equidistant mapping r = f theta, 2 x 0.5 rad = 57.3 degrees.
    fov = field_of_view_deg(fisheye, 23.06, sensor_width_mm=10.0)
    assert fov == pytest.approx(math.degrees(1.0), abs=1.0)
    assert field_of_view_deg(fisheye, 23.06, sensor_width_mm=40.0) is None


def test_cli_prints_json(capsys):
    assert main([str(LENS_DIRECTORY / "singlet_bk7_100mm.lens"), "--focus-distance", "1000"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["paraxial"]["efl_mm"] == pytest.approx(100.0, abs=0.01)
    assert report["sensor_distance_mm"]["focus_distance"] > report["sensor_distance_mm"]["infinity"]
    assert report["focus_shift_486_656_mm"]["infinity_paraxial"] == pytest.approx(1.535, abs=0.002)
    assert report["field_of_view_deg"]["traced"] == pytest.approx(2 * math.degrees(math.atan(0.18)), abs=0.5)
    assert report["image_circle_diameter_mm"] is None  # wider than the scan: 2 x (1.5 f + 10 mm)


def test_cli_reports_assumed_glasses_and_bad_files(tmp_path, capsys):
    dat = tmp_path / "lens.dat"
    dat.write_text("# singlet\n0 2 0 10\n50 4 1.62 20\n-50 0 1 20\n")
    assert main([str(dat), "--wavelength", "550"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["wavelength_nm"] == 550.0
    assert any("n_d 1.62" in note and "S-NBM51" in note for note in report["notes"])
    bad = tmp_path / "bad.dat"
    bad.write_text("0 2 0\n")
    done = subprocess.run([sys.executable, "-m", "engine.tracer.lens", str(bad)], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and done.stdout == ""
    assert "bad.dat, line 1: expected 4 columns" in done.stderr
