"""operators/farm_submit.py without a farm: the job a scene describes, its summary, and the errors
that stop a submission before anything is written. (Submitting for real: test_flamenco_farm.py.)"""

from __future__ import annotations

import bpy
import pytest


@pytest.fixture
def submit_module(prism_addon):
    return prism_addon.operators.farm_submit


def _submit():
    """Run the operator; returns (result, the error it reported or '')."""
    try:
        return bpy.ops.prism.farm_submit(), ""
    except RuntimeError as error:  # an ERROR report raises in background mode
        return {"CANCELLED"}, str(error)


def test_job_follows_the_scene(submit_module, fresh_scene, tmp_path):
    scene = fresh_scene
    scene.frame_start, scene.frame_end, scene.frame_step = 3, 9, 2
    scene.prism.samples, scene.prism.seed, scene.prism.samples_per_pass = 48, 5, 4
    scene.prism.farm.chunks = 4
    scene.prism.farm.output_path = str(tmp_path / "out" / "f_###.exr")
    job = submit_module.farm_job(scene, blendfile="/render/x.blend")
    assert (job.frames, job.samples, job.chunks, job.seed, job.samples_per_pass) == ("3,5,7,9", 48, 4, 5, 4)
    assert job.render_output_path == str(tmp_path / "out" / "f_###.exr")
    assert job.name == scene.name  # untitled file, no job name
    assert submit_module.job_summary(scene) == "4 frames × 4 chunks of 12 samples: 16 render tasks + 4 merges"
    scene.prism.farm.chunks = 1
    assert submit_module.job_summary(scene) == "4 frames of 48 samples: 4 render tasks"


def test_output_relative_to_an_unsaved_file_is_refused(submit_module, fresh_scene, unreachable_url):
    fresh_scene.prism.farm.output_path = "//render/prism_####.exr"
    fresh_scene.prism.farm.manager_url = unreachable_url
    result, error = _submit()
    assert result == {"CANCELLED"}
    assert "is relative to the .blend file, which is not saved yet" in error


def test_samples_that_do_not_split_are_refused_before_contacting_the_manager(submit_module, fresh_scene, tmp_path):
    fresh_scene.prism.samples = 10
    fresh_scene.prism.farm.chunks = 4
    fresh_scene.prism.farm.output_path = str(tmp_path / "prism_####.exr")
    result, error = _submit()
    assert result == {"CANCELLED"} and "10 samples do not split into 4 equal chunks" in error


def test_unreachable_manager_is_reported_and_nothing_is_written(submit_module, fresh_scene, tmp_path, unreachable_url):
    url = unreachable_url
    fresh_scene.prism.farm.manager_url = url
    fresh_scene.prism.farm.output_path = str(tmp_path / "out" / "prism_####.exr")
    result, error = _submit()
    assert result == {"CANCELLED"} and f"Cannot reach Flamenco Manager at {url}" in error
    assert not (tmp_path / "out").exists()  # no snapshot saved for a job that was never submitted
    assert fresh_scene.prism.farm.last_job_id == ""
