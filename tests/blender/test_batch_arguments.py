"""render.py's command line: every wrong argument is refused before Blender opens a file, with
exit status 2 and one line naming the option, the value and what would work."""

from __future__ import annotations

import pytest

from helpers.batch import run_batch

ARGUMENT_CASES = [
    (["--frames", "5..2"], "argument --frames: '5..2': the last frame comes before the first"),
    (["--frames", "1-3"], "argument --frames: frames must look like 1..24 or 7 (got '1-3')"),
    (["--frames", "1048575"], "argument --frames: frame 1048575 is outside Blender's frame range -1048574..1048574"),
    (["--frames", "-2000000..1"], "frame -2000000 is outside Blender's frame range"),
    (["--samples", "0"], "--samples must be at least 1 (got 0)"),
    (["--samples", "3000000000"], "--samples must be at most 2147483647, the Samples setting's limit"),
    (["--seed", "-1"], "--seed must be between 0 and 4294967295: Prism's seeds are 32-bit (got -1)"),
    (["--seed", "4294967296"], "--seed must be between 0 and 4294967295"),
    (["--threads", "-1"], "--threads must be between 0 (all cores) and 1024 (got -1)"),
    (["--threads", "100000"], "--threads must be between 0 (all cores) and 1024 (got 100000)"),
    (["--chunk-seed", "1"], "--chunk-seed needs --samples (the chunk's sample count)"),
    (["--chunk-seed", "-1", "--samples", "4"], "--chunk-seed must be 0 or more (got -1)"),
    (["--chunk-seed", "2000000000", "--samples", "4"],
     "--chunk-seed 2000000000 with --samples 4 ends at sample 8000000004, past the 4294967296 samples"),
    (["--chunk-seed", "1", "--samples", "4", "--frames", "1..2"],
     "--chunk-seed renders one frame: give --frames a single frame, e.g. --frames 1 (got 1..2)"),
    (["--chunk-seed", "1", "--samples", "4", "--keep-partial"], "a partial chunk cannot merge): leave out --keep-partial"),
    (["--expect-samples", "8"], "--expect-samples checks what --merge adds up to: use it with --merge"),
    (["--output", "out.jpg"], "--output must end in .png or .exr (got 'out.jpg')"),
    (["--lens-diagram", "lens.svg"], "--lens-diagram must end in .png (got 'lens.svg')"),
    (["--noise-threshold", "1.5"], "--noise-threshold must be between 0 (off) and 1, e.g. 0.01 (got 1.5)"),
    (["--min-samples", "-3"], "--min-samples must be 0 (automatic) or more (got -3)"),
    (["--time-limit", "-1"], "--time-limit must be 0 (no limit) or a number of seconds (got -1.0)"),
    (["--time-limit", "nan"], "--time-limit must be 0 (no limit) or a number of seconds (got nan)"),
    (["--chunk-seed", "0", "--samples", "4", "--time-limit", "9"], "leave out --noise-threshold and --time-limit"),
    (["--samples", "many"], "argument --samples: invalid int value: 'many'"),
    (["--bogus"], "unrecognized arguments: --bogus"),
]


@pytest.mark.parametrize(("arguments", "message"), ARGUMENT_CASES, ids=[" ".join(a) for a, _ in ARGUMENT_CASES])
def test_wrong_arguments_exit_2_naming_the_option(prism_addon, capsys, bad_input, arguments, message):
    status, line = run_batch(capsys, "scene.blend", "--output", "out.exr", *arguments, in_blender=False)
    assert status == 2
    assert line.startswith("render.py: error: ") and message in line
    bad_input(f"render.py scene.blend --output out.exr {' '.join(arguments)}", status, line)


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--samples", "4"], "give --output (an image to render), --lens-diagram, or both"),
        (["--output", "out.exr"], "give the .blend file to render"),
        (["scene.blend", "--merge", "a.exr", "--output", "m.exr"], "--merge takes chunk EXRs, not a .blend file"),
        (["--merge", "a.exr", "--output", "m.exr", "--keep-partial"], "--merge writes the whole merged image or nothing"),
        (["--merge", "a.exr", "--output", "m.exr", "--expect-samples", "0"],
         "--expect-samples must be between 1 and 4294967296 (got 0)"),
        (["scene.blend", "--chunk-seed", "0", "--samples", "2", "--output", "c.png"], "--chunk-seed writes an EXR"),
        (["scene.blend", "--lens-diagram", "l.png", "--keep-partial"], "--keep-partial keeps an unfinished --output image"),
        (["--merge", "a.exr", "b.exr", "--output", "a.exr"], "--output 'a.exr' is one of the chunks to merge"),
        (["scene.blend", "--output", "x.png", "--lens-diagram", "x.png"], "--lens-diagram and --output name the same file"),
    ],
)
def test_wrong_combinations_exit_2(prism_addon, capsys, bad_input, arguments, message):
    status, line = run_batch(capsys, *arguments, in_blender=False)
    assert (status, message in line) == (2, True), line
    bad_input(f"render.py {' '.join(arguments)}", status, line)


def test_output_that_is_a_folder_is_refused(prism_addon, capsys, tmp_path, bad_input):
    folder = tmp_path / "render.exr"
    folder.mkdir()
    status, line = run_batch(capsys, "scene.blend", "--output", folder, in_blender=False)
    assert status == 2 and f"--output '{folder}' is a folder: give a file name ending in .png or .exr" in line
    bad_input("--output names an existing folder", status, line)


def test_negative_frame_ranges_are_frames_not_options(prism_addon):
    import importlib

    arguments = importlib.import_module(f"{prism_addon.__name__}.engine.batch.arguments")
    parsed = arguments.parse_arguments(["scene.blend", "--frames", "-5..-2", "--output", "o.png"], in_blender=False)
    assert parsed.frames == (-5, -2)
    assert arguments.parse_arguments(["s.blend", "--frames=-3", "--output", "o.png"], in_blender=False).frames == (-3, -3)
