"""End to end on a real Flamenco farm (Manager + three Workers on loopback, see conftest.py): the
``prism-render`` job type submitted from the Farm panel's operator through the REST API, rendered
by the workers (Blender = the bpy shim running render.py), compared with single-process renders.

The scene is tiny (16x16, 6 samples) and animated (the light rises on frame 2), so every task is a
second or two; most of the test's time is the workers asking the Manager for work every few seconds.
"""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import build_lit_card_scene, image_pixels

SAMPLES, CHUNKS, SEED = 6, 3, 7


@pytest.fixture
def animated_scene(fresh_scene, flamenco_farm):
    """The lit card, light moving between frames 1 and 2, saved on the farm's shared storage."""
    build_lit_card_scene(resolution=(16, 16))
    bulb = bpy.data.objects["Bulb"]
    for frame, height_m in ((1, 2.0), (2, 4.0)):
        bulb.location = (0.3, 0.2, height_m)
        bulb.keyframe_insert("location", frame=frame)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 2
    scene.prism.samples, scene.prism.seed, scene.prism.threads = SAMPLES, SEED, 1
    scene.prism.farm.manager_url = flamenco_farm.url
    return scene


def _save(path):
    """Save the open file as ``path`` (the operator then saves its own snapshot beside the output)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=str(path))


def _submit(flamenco_farm):
    assert bpy.ops.prism.farm_submit() == {"FINISHED"}
    job_id = bpy.context.scene.prism.farm.last_job_id
    job = flamenco_farm.wait_for_job(job_id)
    assert job["status"] == "completed", f"{job['status']}: {job['activity']}\n{flamenco_farm.task_logs(job_id)}"
    return job, flamenco_farm.manager.job_tasks(job_id)


def _render_in_process(scene, frame, *arguments):
    """render.py in this process, as ``blender -b -P render.py --`` would run it on ``frame``."""
    render = importlib.import_module("render")
    scene.frame_set(frame)
    assert render.main([str(a) for a in arguments], in_blender=True) == 0


def test_job_type_is_installed_with_its_settings(flamenco_farm):
    job_type = flamenco_farm.manager.job_type("prism-render")
    assert job_type["label"] == "Prism Render"
    keys = {setting["key"] for setting in job_type["settings"]}
    assert keys == {"blendfile", "frames", "samples", "chunks", "samples_per_pass", "seed", "render_output_path",
                    "render_script"}


def test_manager_compiles_a_job_with_only_the_required_settings(flamenco_farm):
    document = {"name": "minimal", "type": "prism-render", "priority": 50, "submitter_platform": "linux",
                "settings": {"blendfile": "/render/scene.blend", "frames": "1-3, 7", "samples": 8,
                             "chunks": 1, "render_output_path": "/render/frame.png"}}
    flamenco_farm.manager.check_job(document)  # seed 0 and {prism}/render.py by default


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"samples": 10}, "samples (10) is not a multiple of chunks (3)"),
        ({"render_output_path": "//render/frame_####.exr"}, "is not an absolute path"),
        ({"render_output_path": "/render/frame_####.jpg"}, "render_output_path '/render/frame_####.jpg' must end in "
                                                            ".exr or .png"),
        ({"samples_per_pass": 0}, "setting 'samples_per_pass' must be a whole number of at least 1"),
        ({"frames": "one to ten"}, "frames 'one to ten' is not a frame range"),
        ({"chunks": 0}, "setting 'chunks' must be a whole number of at least 1"),
    ],
)
def test_manager_refuses_settings_that_cannot_render(flamenco_farm, changes, message):
    from farm.manager import FlamencoError
    from farm.submission import PrismFarmJob

    job = PrismFarmJob(name="bad", blendfile="/render/scene.blend", frames="1..2", samples=9, chunks=3, seed=0,
                       render_output_path="/render/frame_####.exr")
    document = job.submitted_job()
    document["settings"].update(changes)
    with pytest.raises(FlamencoError, match="HTTP 400") as refused:
        flamenco_farm.manager.check_job(document)
    assert message in str(refused.value)


def test_chunks_on_workers_merge_into_the_frames_of_single_renders(animated_scene, flamenco_farm, tmp_path):
    shared = flamenco_farm.shared / "chunked"
    animated_scene.prism.farm.chunks = CHUNKS
    animated_scene.prism.farm.output_path = str(shared / "frames" / "card_##.png")
    animated_scene.view_settings.look = "AgX - Punchy"  # the PNGs follow the scene's picture settings
    # The single-process references first: they also compile any kernels the workers then find cached.
    for frame in (1, 2):
        _render_in_process(animated_scene, frame, "--samples", SAMPLES, "--seed", SEED,
                           "--output", tmp_path / f"single_{frame}.png")
        _render_in_process(animated_scene, frame, "--chunk-seed", 0, "--samples", SAMPLES, "--seed", SEED,
                           "--output", tmp_path / f"single_{frame}.exr")
    _save(shared / "card.blend")
    # One chunk of one frame crashes on the first worker that takes it; Flamenco must retry it elsewhere.
    flamenco_farm.fail_once("frame_####_chunk_0001.exr")

    job, tasks = _submit(flamenco_farm)

    names = sorted(task["name"] for task in tasks)
    assert names == sorted([f"render frame {f} chunk {k}/3" for f in (1, 2) for k in (1, 2, 3)]
                           + ["merge frame 1", "merge frame 2"])
    # Progress: a chunk of 2 samples renders 2 passes (Samples per Pass 1), each a step the worker counted
    # from render.py's "Time: …" line and sent as it came; a merge is one step.
    for task in tasks:
        passes = 1 if task["name"].startswith("merge") else SAMPLES // CHUNKS
        assert task["steps_completed"] == task["steps_total"] == passes, task["name"]
        if passes > 1:
            assert flamenco_farm.steps_logged(task["id"]) == passes, f"{task['name']}: progress advanced per pass"
    assert job["steps_completed"] == job["steps_total"] == 6 * SAMPLES // CHUNKS + 2
    retried = [t for t in (flamenco_farm.manager.task(task["id"]) for task in tasks) if t.get("failed_by_workers")]
    assert [t["name"].rsplit(" ", 1)[-1] for t in retried] == ["2/3"], "exactly one chunk failed once"
    assert retried[0]["status"] == "completed"
    assert retried[0]["worker"]["id"] not in {w["id"] for w in retried[0]["failed_by_workers"]}

    # Each frame's PNG is the PNG of one render of all its samples.
    for frame in (1, 2):
        farm_frame = shared / "frames" / f"card_{frame:02d}.png"
        single = image_pixels(tmp_path / f"single_{frame}.png")
        assert np.array_equal(image_pixels(farm_frame), single), f"frame {frame}"
    # The merges printed "Saved: '…/card_0N.png'": the worker read it and sent the PNG to the Manager.
    assert flamenco_farm.last_rendered(job["id"]), "no last-rendered image: Flamenco did not see a Saved: line"

    # The merge task, run again into an EXR: the float image of one render, bit for bit.
    merges = {t["name"]: flamenco_farm.manager.task(t["id"])["commands"][0] for t in tasks if "merge" in t["name"]}
    chunks = importlib.import_module("prism_spectral.engine.render.chunks")
    means = []
    for frame in (1, 2):
        command = merges[f"merge frame {frame}"]
        exr = tmp_path / f"merged_{frame}.exr"
        args = command["parameters"]["args"]
        as_exr = {**command, "parameters": {**command["parameters"], "args": args[:-1] + [str(exr)]}}
        assert flamenco_farm.run_blender_command(as_exr).returncode == 0
        merged, single = chunks.read_chunk(exr), chunks.read_chunk(tmp_path / f"single_{frame}.exr")
        assert merged.samples == single.samples == SAMPLES and merged.frame == str(frame)
        assert np.array_equal(merged.mean.astype(np.float32), single.mean.astype(np.float32)), f"frame {frame}"
        assert np.abs(merged.mean - single.mean).max() <= 1e-12 * max(1.0, single.mean.max())
        means.append(merged.mean.mean())
    assert means[1] < 0.6 * means[0]  # each task rendered its own frame: the light rose on frame 2

    # The merge task names every chunk of its frame and the samples they must add up to, and refuses to
    # write with one left out, missing, duplicated or of another frame.
    command = merges["merge frame 1"]
    args = command["parameters"]["args"]
    listed = args[args.index("--merge") + 1 : args.index("--expect-samples")]
    assert args[args.index("--expect-samples") + 1] == str(SAMPLES)
    on_disk = sorted((shared / "frames" / "prism-chunks" / job["id"]).glob("frame_0001_chunk_*.exr"))
    assert listed == [str(path) for path in on_disk] and len(listed) == CHUNKS
    final = shared / "frames" / "card_01.png"
    finished = final.read_bytes()
    left_out = {**command, "parameters": {**command["parameters"], "args": [a for a in args if a != listed[1]]}}
    gap = flamenco_farm.run_blender_command(left_out)
    assert gap.returncode == 1 and (
        "The 2 chunks hold 4 of the 6 samples --expect-samples asks for: samples 2..3 are missing (render "
        "--chunk-seed 1 with --samples 2)." in gap.stderr)
    on_disk[2].unlink()
    missing = flamenco_farm.run_blender_command(command)
    assert missing.returncode == 1 and f"Chunk '{on_disk[2]}' does not exist" in missing.stderr
    on_disk[2].write_bytes(on_disk[1].read_bytes())
    duplicated = flamenco_farm.run_blender_command(command)
    assert duplicated.returncode == 1 and "contain the same samples" in duplicated.stderr
    on_disk[2].write_bytes(on_disk[2].with_name("frame_0002_chunk_0002.exr").read_bytes())
    other_frame = flamenco_farm.run_blender_command(command)
    assert other_frame.returncode == 1 and f"Chunk '{on_disk[2]}' is frame 2 but '{on_disk[0]}' is frame 1" in (
        other_frame.stderr)
    assert final.read_bytes() == finished


def test_one_chunk_renders_plain_frames_without_merges(animated_scene, flamenco_farm, tmp_path):
    shared = flamenco_farm.shared / "plain"
    animated_scene.prism.farm.chunks = 1
    animated_scene.prism.farm.output_path = str(shared / "frames" / "card.exr")
    for frame in (1, 2):
        _render_in_process(animated_scene, frame, "--frames", frame, "--samples", SAMPLES, "--seed", SEED,
                           "--output", tmp_path / "card.exr")
    _save(shared / "card.blend")

    job, tasks = _submit(flamenco_farm)

    assert sorted(task["name"] for task in tasks) == ["render frame 1", "render frame 2"]
    for task in tasks:  # a pass a step: 6 samples, Samples per Pass 1
        assert task["steps_completed"] == task["steps_total"] == flamenco_farm.steps_logged(task["id"]) == SAMPLES
    for frame in (1, 2):
        farm_frame = shared / "frames" / f"card_{frame:04d}.exr"  # render.py's numbering without #
        single = image_pixels(tmp_path / f"card_{frame:04d}.exr")
        assert np.array_equal(image_pixels(farm_frame), single), f"frame {frame}"


def test_a_manager_without_the_job_type_says_how_to_install_it(flamenco_farm):
    from farm.manager import FlamencoError

    with pytest.raises(FlamencoError, match="has no 'prism-render-v0' job type: copy Prism's farm/prism_render.js "
                                            "into the scripts/ folder next to the flamenco-manager executable"):
        flamenco_farm.manager.job_type("prism-render-v0")
