"""Batch renders in process (the ``blender -b -P render.py --`` argument path): chunks that merge
to the single render bit for bit, frame ranges, and merge errors."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import build_lit_card_scene


@pytest.fixture
def batch(prism_addon, fresh_scene):
    build_lit_card_scene(resolution=(16, 12))
    return importlib.import_module("render"), importlib.import_module(f"{prism_addon.__name__}.engine.chunks")


def _run(render, *arguments):
    return render.main([str(a) for a in arguments], in_blender=True)


def test_chunks_merge_bit_identical_to_one_render(batch, tmp_path, capsys):
    render, chunks = batch
    for k in (0, 1, 2):
        assert _run(render, "--chunk-seed", k, "--samples", 2, "--seed", 7, "--output", tmp_path / f"chunk_{k}.exr") == 0
    assert _run(render, "--chunk-seed", 0, "--samples", 6, "--seed", 7, "--output", tmp_path / "single.exr") == 0
    assert _run(render, "--merge", *(tmp_path / f"chunk_{k}.exr" for k in (2, 0, 1)), "--output", tmp_path / "merged.exr") == 0
    assert "merged 3 chunks, 6 samples per pixel" in capsys.readouterr().err

    merged, single = chunks.read_chunk(tmp_path / "merged.exr"), chunks.read_chunk(tmp_path / "single.exr")
    assert merged.samples == single.samples == 6
    assert np.array_equal(merged.mean.astype(np.float32), single.mean.astype(np.float32))
    assert np.abs(merged.mean - single.mean).max() <= 1e-12 * max(1.0, single.mean.max())
    # Each chunk alone is a noisier estimate of the same image.
    first = chunks.read_chunk(tmp_path / "chunk_0.exr")
    assert first.samples == 2 and not np.array_equal(first.mean, single.mean)
    assert first.mean.mean() == pytest.approx(single.mean.mean(), rel=0.1)

    # The plain EXR of the same render (Blender's writer, scene-linear) holds the same float32 values.
    assert _run(render, "--samples", 6, "--seed", 7, "--output", tmp_path / "plain.exr") == 0
    image = bpy.data.images.load(str(tmp_path / "plain.exr"))
    pixels = np.empty(16 * 12 * 4, np.float32)
    image.pixels.foreach_get(pixels)
    plain = pixels.reshape(12, 16, 4)[::-1, :, :3]
    assert np.array_equal(plain, single.mean.astype(np.float32))


def test_merge_rejects_overlaps_foreign_files_and_size_mismatches(batch, tmp_path, capsys):
    render, chunks = batch
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--output", tmp_path / "a.exr") == 0
    assert _run(render, "--merge", tmp_path / "a.exr", tmp_path / "a.exr", "--output", tmp_path / "m.exr") == 1
    assert "contain the same samples" in capsys.readouterr().err
    assert _run(render, "--samples", 1, "--output", tmp_path / "plain.exr") == 0
    assert _run(render, "--merge", tmp_path / "a.exr", tmp_path / "plain.exr", "--output", tmp_path / "m.exr") == 1
    assert "has no Prism sample count: merge only chunks written with --chunk-seed" in capsys.readouterr().err
    chunks.write_exr(tmp_path / "small.exr", np.zeros((4, 4, 3)), samples=1, sample_offset=1)
    assert _run(render, "--merge", tmp_path / "a.exr", tmp_path / "small.exr", "--output", tmp_path / "m.exr") == 1
    assert "merge chunks of the same render only" in capsys.readouterr().err
    assert _run(render, "--merge", tmp_path / "missing.exr", "--output", tmp_path / "m.exr") == 1
    assert "missing.exr' does not exist" in capsys.readouterr().err
    assert not (tmp_path / "m.exr").exists()


def test_frame_ranges_number_the_outputs(batch, tmp_path, capsys):
    render, _ = batch
    scene = bpy.context.scene
    bulb = bpy.data.objects["Bulb"]
    bulb.location = (0.3, 0.2, 2.0)
    bulb.keyframe_insert("location", frame=1)
    bulb.location = (0.3, 0.2, 4.0)
    bulb.keyframe_insert("location", frame=2)
    assert _run(render, "--frames", "1..2", "--samples", 1, "--threads", 1, "--output", tmp_path / "shot_##.exr") == 0
    assert (tmp_path / "shot_01.exr").is_file() and (tmp_path / "shot_02.exr").is_file()
    err = capsys.readouterr().err
    assert "Prism: frame 2 (2/2)" in err and "1/1 spp" in err  # progress on stderr
    means = []
    for frame in (1, 2):
        image = bpy.data.images.load(str(tmp_path / f"shot_0{frame}.exr"))
        means.append(np.array(image.pixels[:]).reshape(-1, 4)[:, :3].mean())
    assert means[1] < 0.6 * means[0]  # the light moved away on frame 2: the frames differ
    assert _run(render, "--frames", "3", "--samples", 1, "--output", tmp_path / "still.png") == 0
    assert (tmp_path / "still_0003.png").is_file()
    assert scene.frame_current == 3
