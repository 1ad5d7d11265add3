"""Files render.py cannot use: a missing or foreign .blend, an output folder that cannot be made;
each is one line naming the file and the fix, exit status 1, and nothing written."""

from __future__ import annotations

import bpy

from helpers.batch import run_batch
from helpers.bpy_scenes import build_lit_card_scene


def test_blend_files_that_cannot_open(prism_addon, capsys, tmp_path, bad_input):
    text = tmp_path / "notes.blend"
    text.write_text("not a blend file")
    (tmp_path / "shots.blend").mkdir()
    cases = [
        ("a .blend file that does not exist", tmp_path / "nope.blend", "nope.blend' does not exist: check the path."),
        ("a text file named .blend", text, "notes.blend' cannot be opened ("),
        ("a folder named .blend", tmp_path / "shots.blend", "shots.blend' is a folder: give the .blend file itself."),
    ]
    for description, path, message in cases:
        status, line = run_batch(capsys, path, "--output", tmp_path / "x.png", in_blender=False)
        assert (status, message in line) == (1, True), line
        assert "unexpected" not in line
        bad_input(description, status, line)
    assert not (tmp_path / "x.png").exists()


def test_output_folder_that_cannot_be_made(fresh_scene, capsys, tmp_path, bad_input):
    build_lit_card_scene(resolution=(8, 8))
    (tmp_path / "taken").write_text("a file where the output folder should be")
    output = tmp_path / "taken" / "render.png"
    status, line = run_batch(capsys, "--samples", 1, "--output", output)
    assert status == 1
    assert line == f"Prism: error: Cannot write '{output}': '{output.parent}' is a file, not a folder. Choose another output folder."
    bad_input("--output inside a path where a file stands in for a folder", status, line)


def test_empty_render_border_is_named_before_blender_refuses(fresh_scene, capsys, tmp_path, bad_input):
    build_lit_card_scene(resolution=(8, 8))
    render = bpy.context.scene.render
    render.use_border, render.border_min_x, render.border_max_x = True, 0.5, 0.5
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status == 1
    assert line == ("Prism: error: Scene 'Scene': the render border is empty: draw a larger border (Ctrl+B) "
                    "or turn it off.")
    bad_input("a render border (Render Region) of zero width", status, line)
