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

from helpers.bpy_scenes import build_lit_card_scene

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


def _pixels(path):
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)


def test_job_type_is_installed_with_its_settings(flamenco_farm):
    job_type = flamenco_farm.manager.job_type("prism-render")
    assert job_type["label"] == "Prism Render"
    keys = {setting["key"] for setting in job_type["settings"]}
    assert keys == {"blendfile", "frames", "samples", "chunks", "seed", "render_output_path", "render_script"}


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
        ({"render_output_path": "/render/frame_####.png"}, "must end in .exr (merged chunks are written as EXR"),
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


def test_chunks_on_workers_merge_bit_identical_to_single_renders(animated_scene, flamenco_farm, tmp_path):
    shared = flamenco_farm.shared / "chunked"
    animated_scene.prism.farm.chunks = CHUNKS
    animated_scene.prism.farm.output_path = str(shared / "frames" / "card_##.exr")
    # The single-process references first: they also compile any kernels the workers then find cached.
    for frame in (1, 2):
        _render_in_process(animated_scene, frame, "--chunk-seed", 0, "--samples", SAMPLES, "--seed", SEED,
                           "--output", tmp_path / f"single_{frame}.exr")
    _save(shared / "card.blend")
    # One chunk of one frame crashes on the first worker that takes it; Flamenco must retry it elsewhere.
    flamenco_farm.fail_once("chunk_0001.exr")

    job, tasks = _submit(flamenco_farm)

    names = sorted(task["name"] for task in tasks)
    assert names == sorted([f"render frame {f} chunk {k}/3" for f in (1, 2) for k in (1, 2, 3)]
                           + ["merge frame 1", "merge frame 2"])
    assert all(task["steps_completed"] == task["steps_total"] == 1 for task in tasks)  # progress per task
    assert job["steps_completed"] == job["steps_total"] == 8
    retried = [t for t in (flamenco_farm.manager.task(task["id"]) for task in tasks) if t.get("failed_by_workers")]
    assert [t["name"].rsplit(" ", 1)[-1] for t in retried] == ["2/3"], "exactly one chunk failed once"
    assert retried[0]["status"] == "completed"
    assert retried[0]["worker"]["id"] not in {w["id"] for w in retried[0]["failed_by_workers"]}

    chunks = importlib.import_module("prism_spectral.engine.chunks")
    means = []
    for frame in (1, 2):
        merged = chunks.read_chunk(shared / "frames" / f"card_{frame:02d}.exr")
        single = chunks.read_chunk(tmp_path / f"single_{frame}.exr")
        assert merged.samples == single.samples == SAMPLES
        assert np.array_equal(merged.mean.astype(np.float32), single.mean.astype(np.float32)), f"frame {frame}"
        assert np.abs(merged.mean - single.mean).max() <= 1e-12 * max(1.0, single.mean.max())
        means.append(merged.mean.mean())
    assert means[1] < 0.6 * means[0]  # each merge rendered its own frame: the light rose on frame 2

    # The merge task names every chunk of its frame, and refuses to write with one missing or duplicated.
    merge = flamenco_farm.manager.task(next(t["id"] for t in tasks if t["name"] == "merge frame 1"))
    args = merge["commands"][0]["parameters"]["args"]
    listed = args[args.index("--merge") + 1 : args.index("--output")]
    on_disk = sorted((shared / "frames" / "prism-chunks").glob(f"{job['id']}/0001/chunk_*.exr"))
    assert listed == [str(path) for path in on_disk] and len(listed) == CHUNKS
    final = shared / "frames" / "card_01.exr"
    finished = final.read_bytes()
    on_disk[2].unlink()
    missing = flamenco_farm.run_blender_command(merge["commands"][0])
    assert missing.returncode == 1 and f"Chunk '{on_disk[2]}' does not exist" in missing.stderr
    on_disk[2].write_bytes(on_disk[1].read_bytes())
    duplicated = flamenco_farm.run_blender_command(merge["commands"][0])
    assert duplicated.returncode == 1 and "contain the same samples" in duplicated.stderr
    assert final.read_bytes() == finished


def test_one_chunk_renders_plain_frames_without_merges(animated_scene, flamenco_farm, tmp_path):
    shared = flamenco_farm.shared / "plain"
    animated_scene.prism.farm.chunks = 1
    animated_scene.prism.farm.output_path = str(shared / "frames" / "card.png")
    for frame in (1, 2):
        _render_in_process(animated_scene, frame, "--frames", frame, "--samples", SAMPLES, "--seed", SEED,
                           "--output", tmp_path / "card.png")
    _save(shared / "card.blend")

    job, tasks = _submit(flamenco_farm)

    assert sorted(task["name"] for task in tasks) == ["render frame 1", "render frame 2"]
    for frame in (1, 2):
        farm_frame = shared / "frames" / f"card_{frame:04d}.png"  # render.py's numbering without #
        assert np.array_equal(_pixels(farm_frame), _pixels(tmp_path / f"card_{frame:04d}.png")), f"frame {frame}"


def test_a_manager_without_the_job_type_says_how_to_install_it(flamenco_farm):
    from farm.manager import FlamencoError

    with pytest.raises(FlamencoError, match="has no 'prism-render-v0' job type: copy Prism's farm/prism_render.js "
                                            "into the scripts/ folder next to the flamenco-manager executable"):
        flamenco_farm.manager.job_type("prism-render-v0")
