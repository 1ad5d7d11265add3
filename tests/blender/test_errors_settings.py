"""Errors outside the scene's objects: render settings stored past their limits stop the render with a
message naming the scene and the panel, and a real ``render.py`` process exits non-zero with the message.
"""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import bpy
import pytest

from helpers.batch import run_batch
from helpers.error_scenes import base_scene as _base_scene
from helpers.error_scenes import light as _light

REPO_ROOT = Path(__file__).resolve().parents[2]


def _scene_setting(**values):
    def mutate():
        for key, value in values.items():
            bpy.context.scene.prism[key] = value  # past the property's limits, as a script or an old file can

    return mutate


def test_batch_exits_non_zero_with_the_message(fresh_scene, tmp_path):
    _base_scene()
    _light(color_source="BLACKBODY", temperature_k=90000.0)()
    path = tmp_path / "hot.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    completed = subprocess.run(
        [sys.executable, str(REPO_ROOT / "render.py"), str(path), "--output", str(tmp_path / "x.png")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert completed.returncode == 1
    last_line = completed.stderr.strip().splitlines()[-1]
    assert last_line.startswith("Prism: error: Light 'Bulb': blackbody temperature 90000 K is outside")
    assert not (tmp_path / "x.png").exists()


SETTING_CASES = {
    "Samples 0": (dict(samples=0), "Samples must be at least 1 (got 0)."),
    "Samples per Pass -3": (dict(samples_per_pass=-3), "Samples per pass must be at least 1 (got -3)."),
    "Wavelengths per Path 40": (dict(wavelengths_per_path=40), "Wavelengths per path must be between 1 and 16 (got 40)."),
    "Max Bounces -1": (dict(max_bounces=-1), "Max bounces cannot be negative (got -1)."),
}


@pytest.mark.parametrize("case", list(SETTING_CASES))
def test_scene_settings_stored_past_their_limits(prism_addon, fresh_scene, tmp_path, capsys, bad_input, case):
    """As a script or an old file can store them: the message says which scene and panel."""
    requests = importlib.import_module(f"{prism_addon.__name__}.engine.render.request")
    values, message = SETTING_CASES[case]
    _base_scene()
    _scene_setting(**values)()
    expected = f"Scene 'Scene', Render Properties ▸ Prism: {message}"
    with requests.render_request() as report, pytest.raises(RuntimeError):
        bpy.ops.render.render()
    assert report.error == expected
    status, line = run_batch(capsys, "--output", tmp_path / "x.png")
    assert (status, line) == (1, f"Prism: error: {expected}")
    bad_input(f"scene setting {case} (stored past the UI's limit)", status, line)
