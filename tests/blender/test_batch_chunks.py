"""Batch renders in process (the ``blender -b -P render.py --`` argument path): chunks that merge
to the single render bit for bit, chunks that carry what they were rendered from, and merges that
refuse chunks which do not belong together."""

from __future__ import annotations

import importlib
import json
import re

import bpy
import numpy as np
import pytest

from helpers.batch import run_batch, run_batch_stderr
from helpers.bpy_scenes import build_lit_card_scene, image_pixels


@pytest.fixture
def batch(prism_addon, fresh_scene):
    build_lit_card_scene(resolution=(16, 12))
    return importlib.import_module("render"), importlib.import_module(f"{prism_addon.__name__}.engine.render.chunks")


def _run(render, *arguments):
    return render.main([str(a) for a in arguments], in_blender=True)


def test_chunks_merge_bit_identical_to_one_render(batch, tmp_path, capsys):
    render, chunks = batch
    for k in (0, 1, 2):
        assert _run(render, "--chunk-seed", k, "--samples", 2, "--seed", 7, "--output", tmp_path / f"chunk_{k}.exr") == 0
    assert _run(render, "--chunk-seed", 0, "--samples", 6, "--seed", 7, "--output", tmp_path / "single.exr") == 0
    assert _run(render, "--merge", *(tmp_path / f"chunk_{k}.exr" for k in (2, 0, 1)), "--output", tmp_path / "merged.exr") == 0
    assert "merged 3 chunks of frame 1, 6 samples per pixel" in capsys.readouterr().err

    merged, single = chunks.read_chunk(tmp_path / "merged.exr"), chunks.read_chunk(tmp_path / "single.exr")
    assert merged.samples == single.samples == 6
    assert merged.sample_ranges == single.sample_ranges == ((0, 6),)
    assert merged.fingerprint == single.fingerprint and merged.seed == single.seed == 7
    assert np.array_equal(merged.mean.astype(np.float32), single.mean.astype(np.float32))
    assert np.abs(merged.mean - single.mean).max() <= 1e-12 * max(1.0, single.mean.max())
    # Each chunk alone is a noisier estimate of the same image.
    first = chunks.read_chunk(tmp_path / "chunk_0.exr")
    assert first.samples == 2 and not np.array_equal(first.mean, single.mean)
    assert first.mean.mean() == pytest.approx(single.mean.mean(), rel=0.1)

    # The plain EXR of the same render (Blender's writer, scene-linear) holds the same float32 values.
    assert _run(render, "--samples", 6, "--seed", 7, "--output", tmp_path / "plain.exr") == 0
    plain = image_pixels(tmp_path / "plain.exr")[::-1, :, :3]
    assert np.array_equal(plain, single.mean.astype(np.float32))


def test_merge_rejects_overlaps_foreign_files_and_size_mismatches(batch, tmp_path, capsys, bad_input):
    render, chunks = batch
    merged = tmp_path / "m.exr"
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--output", tmp_path / "a.exr") == 0
    assert _run(render, "--samples", 1, "--output", tmp_path / "plain.exr") == 0
    small = chunks.read_chunk(tmp_path / "a.exr")
    small.mean, small.sample_ranges = np.zeros((4, 4, 3)), ((1, 2),)
    chunks.write_chunk(tmp_path / "small.exr", small)
    (tmp_path / "folder.exr").mkdir()
    cases = [
        ("the same chunk twice", [tmp_path / "a.exr", tmp_path / "a.exr"], "contain the same samples (from sample 0)"),
        ("a plain render as a chunk", [tmp_path / "a.exr", tmp_path / "plain.exr"],
         "has no Prism sample count: it is not a chunk. Merge only chunks written with --chunk-seed"),
        ("chunks of different sizes", [tmp_path / "a.exr", tmp_path / "small.exr"], "merge chunks of the same render only"),
        ("a chunk that does not exist", [tmp_path / "missing.exr"], "missing.exr' does not exist: check the path"),
        ("a folder as a chunk", [tmp_path / "folder.exr"], "folder.exr' is a folder: give the chunk EXR files"),
    ]
    for description, inputs, message in cases:
        status, line = run_batch(capsys, "--merge", *inputs, "--output", merged)
        assert (status, message in line) == (1, True), line
        bad_input(f"--merge: {description}", status, line)
    assert not merged.exists()


def _edit_chunk(path, edit):
    """Rewrite the EXR at ``path`` after ``edit(pixels [H, W, C], spec)``, keeping its attributes."""
    chunks = importlib.import_module("prism_spectral.engine.render.chunks")
    oiio = chunks._oiio()
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, spec.nchannels, "float"), np.float32).reshape(spec.height, spec.width, -1)
    image.close()
    edit(pixels, spec)
    output = oiio.ImageOutput.create(str(path))
    output.open(str(path), spec)
    output.write_image(np.ascontiguousarray(pixels))
    output.close()


def test_merge_of_chunks_from_two_scenes_is_refused(batch, tmp_path, capsys, bad_input):
    render, _ = batch
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--output", tmp_path / "a.exr") == 0
    bpy.data.objects["Card"].location.x += 0.25  # same size, same settings, another scene
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--output", tmp_path / "b.exr") == 0
    (tmp_path / "m.exr").write_bytes(b"an earlier merge")
    status, line = run_batch(capsys, "--merge", tmp_path / "a.exr", tmp_path / "b.exr", "--output", tmp_path / "m.exr")
    assert status == 1
    assert "a.exr' and '" in line and "b.exr' come from different renders (their geometry differ)" in line
    assert (tmp_path / "m.exr").read_bytes() == b"an earlier merge"
    bad_input("--merge: chunks rendered from two different scenes of the same size", status, line)

    bpy.data.objects["Card"].location.x -= 0.25  # back to the first scene, another seed
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--seed", 5, "--output", tmp_path / "c.exr") == 0
    status, line = run_batch(capsys, "--merge", tmp_path / "a.exr", tmp_path / "c.exr", "--output", tmp_path / "m.exr")
    assert status == 1 and "(seed 0) and '" in line and "(seed 5) have different seeds" in line
    bad_input("--merge: chunks rendered with different --seed", status, line)

    bpy.context.scene.view_settings.exposure = 1.0  # the same render, another picture from it
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--output", tmp_path / "e.exr") == 0
    status, line = run_batch(capsys, "--merge", tmp_path / "a.exr", tmp_path / "e.exr", "--output", tmp_path / "m.exr")
    assert status == 1 and "e.exr' come from scenes with different Color Management or PNG output settings" in line
    bad_input("--merge: chunks whose scenes differ in Color Management (exposure)", status, line)
    bpy.context.scene.view_settings.exposure = 0.0

    bpy.context.scene.prism.max_bounces = 2  # the same scene, other settings
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--output", tmp_path / "d.exr") == 0
    status, line = run_batch(capsys, "--merge", tmp_path / "a.exr", tmp_path / "d.exr", "--output", tmp_path / "m.exr")
    assert status == 1 and "come from different renders (their settings differ)" in line


def test_merge_refuses_damaged_edited_and_non_finite_chunks(batch, tmp_path, capsys, bad_input):
    render, chunks = batch
    good = tmp_path / "good.exr"
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--output", good) == 0

    def damaged(name, edit):
        path = tmp_path / name
        path.write_bytes(good.read_bytes())
        edit(path)
        return path

    def poke(value):
        def edit(pixels, spec):
            pixels[3, 5, 1] = value
        return lambda path: _edit_chunk(path, edit)

    def attribute(name, value):
        return lambda path: _edit_chunk(path, lambda pixels, spec: spec.attribute(name, value))

    cases = [
        ("a chunk cut short (truncated file)", damaged("cut.exr", lambda p: p.write_bytes(good.read_bytes()[:-300])),
         "cut.exr' is damaged"),
        ("a chunk with a NaN pixel", damaged("nan.exr", poke(np.nan)),
         "nan.exr' holds 1 pixel(s) that are NaN or infinite (the first at x=5, y=3 from the top)"),
        ("a chunk with an infinite pixel", damaged("inf.exr", poke(np.inf)), "inf.exr' holds 1 pixel(s) that are NaN"),
        ("a chunk whose pixels were edited", damaged("edited.exr", poke(0.5)),
         "edited.exr' does not match its checksum: it was damaged or edited after Prism wrote it"),
        ("a chunk whose seed attribute was edited", damaged("seed.exr", attribute("prism:seed", "3")),
         "seed.exr' does not match its checksum"),
        ("a chunk with an unreadable sample range", damaged("ranges.exr", attribute("prism:sample_ranges", "[[2, 1]]")),
         "ranges.exr' has damaged Prism attributes"),
        ("a chunk of an earlier Prism (no fingerprint)",
         damaged("old.exr", lambda p: _edit_chunk(p, lambda px, spec: (spec.erase_attribute("prism:chunk"),
                                                                       spec.attribute("prism:samples", 4)))),
         "old.exr' was written by an earlier Prism and carries no fingerprint"),
        ("a text file named .exr", damaged("text.exr", lambda p: p.write_text("not an image")),
         "text.exr' is not a readable EXR image"),
    ]
    for description, path, message in cases:
        status, line = run_batch(capsys, "--merge", good, path, "--output", tmp_path / "m.exr")
        assert (status, message in line) == (1, True), (description, line)
        assert "unexpected" not in line
        bad_input(f"--merge: {description}", status, line)
    assert not (tmp_path / "m.exr").exists()


def test_large_seeds_and_offsets_survive_the_exr_round_trip(batch, tmp_path, capsys):
    render, chunks = batch
    seed, first = 2**32 - 1, 3_000_000_000  # beyond int32: EXR int attributes would wrap
    for k in (first, first + 1):
        assert _run(render, "--chunk-seed", k, "--samples", 1, "--seed", seed, "--output", tmp_path / f"{k}.exr") == 0
    chunk = chunks.read_chunk(tmp_path / f"{first}.exr")
    assert (chunk.seed, chunk.sample_ranges) == (seed, ((first, first + 1),))
    assert _run(render, "--merge", *(tmp_path / f"{k}.exr" for k in (first, first + 1)), "--output", tmp_path / "m.exr") == 0
    merged = chunks.read_chunk(tmp_path / "m.exr")
    assert (merged.seed, merged.sample_ranges, merged.samples) == (seed, ((first, first + 2),), 2)
    assert np.isfinite(merged.mean).all() and merged.mean.mean() > 0.01


def test_merged_chunks_merge_again_without_double_counting(batch, tmp_path):
    render, chunks = batch
    for k in (0, 2, 3):
        assert _run(render, "--chunk-seed", k, "--samples", 1, "--output", tmp_path / f"c{k}.exr") == 0
    assert _run(render, "--merge", tmp_path / "c0.exr", tmp_path / "c2.exr", "--output", tmp_path / "m02.exr") == 0
    assert chunks.read_chunk(tmp_path / "m02.exr").sample_ranges == ((0, 1), (2, 3))
    assert _run(render, "--merge", tmp_path / "m02.exr", tmp_path / "c2.exr", "--output", tmp_path / "x.exr") == 1
    assert _run(render, "--merge", tmp_path / "m02.exr", tmp_path / "c3.exr", "--output", tmp_path / "x.exr") == 0
    assert json.loads(json.dumps(chunks.read_chunk(tmp_path / "x.exr").sample_ranges)) == [[0, 1], [2, 4]]


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
    assert _run(render, "--frames", "-2..-1", "--samples", 1, "--output", tmp_path / "neg_###.png") == 0
    assert (tmp_path / "neg_-02.png").is_file() and (tmp_path / "neg_-01.png").is_file()
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []  # no temporary files left


def test_chunk_samples_must_be_whole_passes(batch, tmp_path, capsys, bad_input):
    bpy.context.scene.prism.samples_per_pass = 2
    status, line = run_batch(capsys, "--chunk-seed", 1, "--samples", 3, "--output", tmp_path / "c.exr")
    assert status == 1 and line == (
        "Prism: error: Chunk offset 3 is not a multiple of Samples per Pass (2): use --samples that is a multiple "
        "of the scene's Samples per Pass."
    )
    assert not (tmp_path / "c.exr").exists()
    bad_input("--chunk-seed 1 --samples 3 with Samples per Pass 2", status, line)


def test_every_pass_prints_a_time_line_that_render_farms_count(batch, tmp_path, capsys):
    bpy.context.scene.prism.samples_per_pass = 2
    status, stderr = run_batch_stderr(capsys, "--samples", 6, "--output", tmp_path / "x.exr")
    assert status == 0, stderr
    # Flamenco's worker counts a step for every line matching ^Time: ([0-9:.]+), as Blender prints per frame.
    times = [line for line in stderr.splitlines() if re.match(r"Time: [0-9:.]+ ", line)]
    assert [line.split(" | ")[2:4] for line in times] == [["Pass 1", "2/6 spp"], ["Pass 2", "4/6 spp"],
                                                         ["Pass 3", "6/6 spp"]]
    stats = importlib.import_module("prism_spectral.engine.render.stats")
    assert [stats.timecode(s) for s in (0.0, 7.254, 3727.25)] == ["00:00.00", "00:07.25", "01:02:07.25"]


def _animate_bulb():
    """The light rises between frames 1 and 2: the frames render differently."""
    bulb = bpy.data.objects["Bulb"]
    for frame, height_m in ((1, 2.0), (2, 4.0)):
        bulb.location = (0.3, 0.2, height_m)
        bulb.keyframe_insert("location", frame=frame)
    return bulb


def test_a_chunk_renders_the_frame_given_and_chunks_of_two_frames_never_merge(batch, tmp_path, capsys, bad_input):
    render, chunks = batch
    scene = bpy.context.scene
    bulb = _animate_bulb()
    scene.frame_set(1)
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--frames", 2, "--output", tmp_path / "c0_##.exr") == 0
    scene.frame_set(2)  # what farm tasks did before --frames: set the frame, then render the current one
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--output", tmp_path / "current.exr") == 0
    by_option, at_current = chunks.read_chunk(tmp_path / "c0_02.exr"), chunks.read_chunk(tmp_path / "current.exr")
    assert by_option.frame == at_current.frame == "2" and by_option.fingerprint == at_current.fingerprint
    assert np.array_equal(by_option.mean, at_current.mean)

    # Nothing moves any more: frames 1 and 2 export the same scene, yet their chunks are not one render's.
    bulb.animation_data_clear()
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--frames", 1, "--output", tmp_path / "a.exr") == 0
    assert _run(render, "--chunk-seed", 1, "--samples", 1, "--frames", 2, "--output", tmp_path / "b.exr") == 0
    first, second = tmp_path / "a_0001.exr", tmp_path / "b_0002.exr"  # --frames numbers a name without '#'
    assert chunks.read_chunk(first).fingerprint != chunks.read_chunk(second).fingerprint
    status, line = run_batch(capsys, "--merge", first, second, "--output", tmp_path / "m.exr")
    assert status == 1 and line == (
        f"Prism: error: Chunk '{second}' is frame 2 but '{first}' is frame 1: merge the chunks of one frame only "
        "(--chunk-seed with --frames F renders a chunk of frame F)."
    )
    assert not (tmp_path / "m.exr").exists()
    bad_input("--merge: a chunk of frame 2 given with frame 1's (a scene where nothing moves)", status, line)


def test_expect_samples_refuses_a_gap_a_missing_end_and_samples_beyond(batch, tmp_path, capsys, bad_input):
    render, chunks = batch
    chunk = [tmp_path / f"c{k}.exr" for k in range(4)]
    for k, path in enumerate(chunk):
        assert _run(render, "--chunk-seed", k, "--samples", 1, "--output", path) == 0
    merged = tmp_path / "m.exr"
    assert _run(render, "--merge", *chunk, "--expect-samples", 4, "--output", merged) == 0
    assert chunks.read_chunk(merged).sample_ranges == ((0, 4),)
    merged.unlink()
    cases = [
        ("--merge: one chunk left out (--expect-samples 4)", [chunk[0], chunk[1], chunk[3]], 4,
         "Prism: error: The 3 chunks hold 3 of the 4 samples --expect-samples asks for: sample 2 is missing "
         "(render --chunk-seed 2 with --samples 1)."),
        ("--merge: the last chunks left out (--expect-samples 4)", chunk[:2], 4,
         "Prism: error: The 2 chunks hold 2 of the 4 samples --expect-samples asks for: samples 2..3 are missing "
         "(render --chunk-seed 2 and 3 with --samples 1)."),
        ("--merge: the first chunk left out (--expect-samples 2)", chunk[1:2], 2,
         "Prism: error: The chunk holds 1 of the 2 samples --expect-samples asks for: sample 0 is missing "
         "(render --chunk-seed 0 with --samples 1)."),
        ("--merge: a chunk past --expect-samples", chunk, 3,
         f"Prism: error: Chunk '{chunk[3]}' holds sample 3, past the 3 samples --expect-samples asks for: leave it "
         "out, or give the frame's real total to --expect-samples."),
    ]
    for description, inputs, expected, message in cases:
        status, line = run_batch(capsys, "--merge", *inputs, "--expect-samples", expected, "--output", merged)
        assert (status, line) == (1, message), description
        bad_input(description, status, line)
    assert not merged.exists()


def _picture_settings(scene):
    """Away from every default that shapes a PNG: view transform, look, exposure, gamma, curves,
    white balance, no dither, 16-bit RGB."""
    view = scene.view_settings
    view.view_transform, view.look = "Filmic", "High Contrast"
    view.exposure, view.gamma = 0.6, 1.2
    view.use_curve_mapping = True
    view.curve_mapping.curves[3].points.new(0.4, 0.55)
    view.curve_mapping.update()
    view.use_white_balance, view.white_balance_temperature = True, 5000.0
    scene.render.dither_intensity = 0.0
    image = scene.render.image_settings
    image.file_format, image.color_depth, image.color_mode = "PNG", "16", "RGB"


def _png(path):
    """Pixels [H, W, 4] (bottom row first) and the PNG's (bit depth, colour type: 2 RGB, 6 RGBA)."""
    header = path.read_bytes()[:26]  # signature, IHDR length and type, width, height, depth, colour type
    return image_pixels(path), (header[24], header[25])


@pytest.mark.parametrize("picture", ["defaults", "graded"])
def test_chunks_merge_into_the_png_of_one_render(batch, tmp_path, capsys, picture):
    render, chunks = batch
    scene = bpy.context.scene
    if picture == "graded":
        _picture_settings(scene)
    assert _run(render, "--samples", 6, "--seed", 3, "--output", tmp_path / "single.png") == 0
    for k in (0, 1, 2):
        assert _run(render, "--chunk-seed", k, "--samples", 2, "--seed", 3, "--output", tmp_path / f"c{k}.exr") == 0
    # The merge uses the chunks' settings, not the open scene's.
    scene.view_settings.view_transform, scene.render.dither_intensity = "Standard", 1.0
    capsys.readouterr()
    status = render.main([str(a) for a in ("--merge", *(tmp_path / f"c{k}.exr" for k in (0, 1, 2)),
                                           "--expect-samples", 6, "--output", tmp_path / "merged_##.png")], True)
    merged_path = tmp_path / "merged_01.png"  # '#': the chunks' frame
    assert status == 0 and capsys.readouterr().err.splitlines()[-1] == f"Saved: '{merged_path}'"
    merged, merged_depth = _png(merged_path)
    single, single_depth = _png(tmp_path / "single.png")
    assert np.array_equal(merged, single), "the merged PNG is the PNG of one render of all the samples"
    assert merged_depth == single_depth == ((16, 2) if picture == "graded" else (8, 6))  # 16-bit RGB, 8-bit RGBA
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []
    assert "Prism PNG output" not in bpy.data.scenes  # the scratch scene is gone


def test_a_png_merge_with_settings_this_blender_lacks_is_refused_and_writes_nothing(batch, tmp_path, capsys, bad_input):
    render, chunks = batch
    assert _run(render, "--chunk-seed", 0, "--samples", 1, "--output", tmp_path / "c.exr") == 0
    foreign = chunks.read_chunk(tmp_path / "c.exr")
    foreign.png_settings["view_settings"]["view_transform"] = "Studio Log 9"  # another studio's OCIO config
    chunks.write_chunk(tmp_path / "foreign.exr", foreign)
    (tmp_path / "m.png").write_bytes(b"yesterday's frame")
    status, line = run_batch(capsys, "--merge", tmp_path / "foreign.exr", "--output", tmp_path / "m.png")
    assert status == 1 and line.startswith(
        f"Prism: error: '{tmp_path / 'foreign.exr'}' was rendered with Color Management ▸ View Transform "
        "'Studio Log 9', which this Blender cannot use (")
    assert line.endswith("write the PNG with the Blender the chunks were rendered with, or merge to EXR.")
    assert (tmp_path / "m.png").read_bytes() == b"yesterday's frame"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.exr", "foreign.exr", "m.png"]
    assert "Prism PNG output" not in bpy.data.scenes
    bad_input("--merge … --output x.png: a chunk's view transform is unknown to this Blender", status, line)


def test_expect_samples_names_many_missing_chunks_as_a_range_and_odd_sizes_without_a_hint(prism_addon):
    chunks = importlib.import_module(f"{prism_addon.__name__}.engine.render.chunks")
    parts = importlib.import_module(f"{prism_addon.__name__}.engine.render.fingerprint").PARTS

    def chunk(start, end, name):
        return chunks.Chunk(mean=np.zeros((2, 2, 3)), seed=0, sample_ranges=((start, end),),
                            fingerprint={part: "1" for part in parts}, png_settings={}, path=name)

    with pytest.raises(chunks.PrismInputError, match=r"The 2 chunks hold 2 of the 12 samples --expect-samples asks "
                       r"for: samples 1\.\.10 are missing \(render the 10 chunks from --chunk-seed 1 to 10 with "
                       r"--samples 1\)\.$"):
        chunks.merge_chunks([chunk(0, 1, "a.exr"), chunk(11, 12, "b.exr")], expect_samples=12)
    with pytest.raises(chunks.PrismInputError, match=r"samples 2\.\.3 are missing\.$"):  # chunks of 2 and 1 samples
        chunks.merge_chunks([chunk(0, 2, "a.exr"), chunk(4, 5, "b.exr")], expect_samples=5)
