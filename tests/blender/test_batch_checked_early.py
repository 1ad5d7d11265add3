"""Settings and paths that used to fail only after the whole render (or not at all) are refused before
anything renders: a spectral output that cannot be written, a band width or filter width of 0, a kernel
cache variable naming a file. One line each naming the setting, the value and the fix; exit status 1."""

from __future__ import annotations

import os

import pytest

from helpers.batch import run_batch_stderr
from helpers.bpy_scenes import build_lit_card_scene


@pytest.fixture
def card(fresh_scene):
    build_lit_card_scene(resolution=(8, 6))
    return fresh_scene


def _refused(capsys, *arguments):
    status, stderr = run_batch_stderr(capsys, "--samples", 1, *arguments)
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert not any(line.startswith("Time:") for line in lines), "refused before rendering"
    return status, lines[-1]


def test_a_spectral_output_under_a_file_is_refused_before_rendering(card, tmp_path, capsys, bad_input):
    (tmp_path / "notes.txt").write_text("a file where a folder should be")
    spectral = tmp_path / "notes.txt" / "bands.exr"
    status, line = _refused(capsys, "--output", tmp_path / "out.png", "--spectral-output", spectral)
    assert (status, line) == (1, "Prism: error: Spectral output (Render ▸ Prism ▸ Spectral Output, or "
                                 f"--spectral-output): Cannot write '{spectral}': '{spectral.parent}' is a file, not a "
                                 "folder. Choose another output folder.")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]
    bad_input("--spectral-output under a regular file", status, line)


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs /proc")
def test_a_spectral_output_in_proc_is_refused_before_rendering(card, tmp_path, capsys, bad_input):
    status, line = _refused(capsys, "--output", tmp_path / "out.png", "--spectral-output", "/proc/bands.exr")
    assert status == 1 and line.startswith("Prism: error: Spectral output (Render ▸ Prism ▸ Spectral Output, or "
                                           "--spectral-output): Cannot write '/proc/bands.exr': "), line
    assert line.endswith("Choose a folder that exists and that you can write to.")
    assert not (tmp_path / "out.png").exists()
    bad_input("--spectral-output into the /proc file system (no file can be created there)", status, line)


def test_a_band_width_of_0_is_refused_before_rendering(card, tmp_path, capsys, bad_input):
    card.prism["spectral_band_nm"] = 0.0  # past the UI's minimum, as a script or an old file can store it
    status, line = _refused(capsys, "--output", tmp_path / "out.png", "--spectral-output", tmp_path / "b.exr")
    assert (status, line) == (1, "Prism: error: Scene 'Scene': Spectral output band width 0 nm is outside 1-100 nm: "
                                 "set Render ▸ Prism ▸ Spectral Output ▸ Band Width within that range (10 nm gives "
                                 "47 bands).")
    bad_input("Spectral Output ▸ Band Width 0 (stored past the UI's minimum) with --spectral-output", status, line)


def test_a_filter_width_of_0_names_the_width(card, tmp_path, capsys, bad_input):
    card.prism["filter_width_px"] = 0.0
    status, line = _refused(capsys, "--output", tmp_path / "out.png")
    assert (status, line) == (1, "Prism: error: Scene 'Scene', Render Properties ▸ Prism: Filter Width must be above "
                                 "0 pixels (got 0): set it to e.g. 1.5 (the pixel filter's reach in pixels; Blender's "
                                 "smallest is 0.01).")
    bad_input("Pixel Filter Width 0 (stored past the UI's minimum)", status, line)


def test_a_kernel_cache_variable_naming_a_file_is_refused(card, tmp_path, capsys, monkeypatch, bad_input):
    taken = tmp_path / "kernels.txt"
    taken.write_text("not a folder")
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(taken))
    status, line = _refused(capsys, "--output", tmp_path / "out.png")
    assert status == 1 and line.startswith(
        f"Prism: error: PRISM_KERNEL_CACHE is '{taken}', where Prism cannot keep its compiled kernels (it is a "
        "file, not a folder): point PRISM_KERNEL_CACHE at a folder you can write to (it is created if missing), or "
        "unset it to use "), line
    assert taken.read_text() == "not a folder"
    bad_input("PRISM_KERNEL_CACHE naming a file", status, line)
