"""Ctrl-C and SIGTERM sent to a real ``render.py`` process: nothing finished is lost, nothing
unfinished is written under an output's name, and the exit status says the run was interrupted."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import bpy
import pytest

from helpers.batch import last_line
from helpers.bpy_scenes import build_lit_card_scene

REPO_ROOT = Path(__file__).resolve().parents[2]
SLOW_SAMPLES = 100_000  # far more than a test waits for: only a signal ends such a render


def _scene_file(tmp_path, samples_by_frame) -> Path:
    """The lit card scene with the Samples setting keyed per frame (constant between keys)."""
    build_lit_card_scene(resolution=(48, 32))
    scene = bpy.context.scene
    for frame, samples in samples_by_frame.items():
        scene.prism.samples = samples
        scene.prism.keyframe_insert("samples", frame=frame)
    for curve in scene.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "CONSTANT"
    path = tmp_path / "scene.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return path


def _signal_when(arguments, trigger_lines, number, temporary_folder: Path) -> tuple[int, str]:
    """Run render.py with ``temporary_folder`` as its system temporary folder; once every text in
    ``trigger_lines`` has appeared on stderr (in order), send signal ``number``; return the exit
    status and all of stderr."""
    temporary_folder.mkdir(exist_ok=True)
    process = subprocess.Popen(
        [sys.executable, str(REPO_ROOT / "render.py"), *map(str, arguments)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=dict(os.environ, TMPDIR=str(temporary_folder)),
    )
    watchdog = threading.Timer(240, process.kill)  # a hang fails the test instead of the suite
    watchdog.start()
    seen, waiting = [], list(trigger_lines)
    try:
        while waiting:
            line = process.stderr.readline()
            if not line:
                break
            seen.append(line)
            if waiting[0] in line:
                waiting.pop(0)
        assert not waiting, f"render.py ended before printing {waiting[0]!r}:\n{''.join(seen)}"
        process.send_signal(number)
        rest = process.stderr.read()
        status = process.wait(timeout=120)
    finally:
        watchdog.cancel()
        process.kill()
    return status, "".join(seen) + rest


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if ".tmp" in p.name or ".prism-" in p.name)


def test_ctrl_c_keeps_finished_frames_and_never_replaces_an_output_with_a_partial_one(fresh_scene, tmp_path, bad_input):
    blend = _scene_file(tmp_path, {1: 1, 2: SLOW_SAMPLES})
    out = tmp_path / "out"
    out.mkdir()
    for frame in (2, 3):
        (out / f"shot_{frame}.exr").write_bytes(b"finished frame %d from an earlier run" % frame)
    status, stderr = _signal_when(
        [blend, "--frames", "1..3", "--output", out / "shot_#.exr"],
        ["Saved: ", "Prism: frame 2 (2/3)", "| Pass 2 |"],
        signal.SIGINT,
        tmp_path / "tmp",
    )
    assert status == 130, stderr
    assert last_line(stderr) == f"Prism: interrupted by SIGINT: '{out / 'shot_2.exr'}' was not written."
    image = bpy.data.images.load(str(out / "shot_1.exr"))  # finished before Ctrl-C: written, and whole
    assert tuple(image.size) == (48, 32)
    for frame in (2, 3):  # the interrupted frame and the one never started keep the earlier run's files
        assert (out / f"shot_{frame}.exr").read_bytes() == b"finished frame %d from an earlier run" % frame
    assert "Prism: frame 3" not in stderr
    assert _leftovers(out) == []
    assert list((tmp_path / "tmp").iterdir()) == [], "Blender's session folder outlived the process"
    bad_input("Ctrl-C (SIGINT) during frame 2 of --frames 1..3", status, last_line(stderr))


@pytest.mark.parametrize("keep_partial", [True, False], ids=["keep-partial", "default"])
def test_sigterm_leaves_the_output_as_it_was(fresh_scene, tmp_path, keep_partial, bad_input):
    blend = _scene_file(tmp_path, {1: SLOW_SAMPLES})
    output = tmp_path / "still.exr"
    output.write_bytes(b"the good render from yesterday")
    status, stderr = _signal_when(
        [blend, "--output", output, *(["--keep-partial"] if keep_partial else [])], ["| Pass 3 |"], signal.SIGTERM,
        tmp_path / "tmp",
    )
    assert status == 143, stderr
    assert output.read_bytes() == b"the good render from yesterday"
    partial = tmp_path / "still.partial.exr"
    assert partial.is_file() == keep_partial
    if keep_partial:
        assert last_line(stderr).endswith(f"the unfinished image is in '{partial}'.")
        image = bpy.data.images.load(str(partial))
        assert tuple(image.size) == (48, 32) and max(image.pixels[:]) > 0  # passes done before the signal
    assert _leftovers(tmp_path) == []
    assert list((tmp_path / "tmp").iterdir()) == []
    bad_input(f"SIGTERM during a render{' with --keep-partial' if keep_partial else ''}", status, last_line(stderr))

