"""render.py as a command: renders a .blend, and fails clearly on bad input."""

import subprocess
import sys
from pathlib import Path

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, build_lit_card_scene

REPO_ROOT = Path(__file__).resolve().parents[2]


def run_render_script(*arguments):
    """``python render.py ...``; stdout (Blender's own lines) and stderr (Prism's) apart."""
    return subprocess.run(
        [sys.executable, str(REPO_ROOT / "render.py"), *map(str, arguments)],
        capture_output=True,
        text=True,
        timeout=300,
    )


@pytest.fixture
def lit_scene_file(fresh_scene, tmp_path):
    build_lit_card_scene(resolution=(24, 16))
    path = tmp_path / "lit.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return path


def test_renders_png_with_light_and_shadow(lit_scene_file, tmp_path):
    output = tmp_path / "out.png"
    completed = run_render_script(lit_scene_file, "--samples", 2, "--output", output)
    assert completed.returncode == 0, completed.stderr
    # Prism is registered before the file opens: loading it reports no missing engine.
    assert "not available" not in completed.stdout + completed.stderr
    assert completed.stderr.strip().splitlines()[-1] == f"Saved: '{output}'"
    image = bpy.data.images.load(str(output))
    pixels = np.array(image.pixels[:]).reshape(16, 24, 4)[..., :3]
    assert pixels.std() > 0.05, "the render is a flat colour"


def test_numbered_output_takes_the_current_frame_and_only_the_final_file_is_announced(fresh_scene, tmp_path):
    build_lit_card_scene(resolution=(8, 6))
    bpy.context.scene.frame_current = 7
    blend = tmp_path / "at_frame_7.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    completed = run_render_script(blend, "--samples", 1, "--output", tmp_path / "out_###.png")
    assert completed.returncode == 0, completed.stderr
    final = tmp_path / "out_007.png"  # as Blender numbers a still: '#' without --frames is the current frame
    assert sorted(path.name for path in tmp_path.iterdir()) == ["at_frame_7.blend", "out_007.png"]
    printed = completed.stdout + completed.stderr
    assert printed.count("Saved: ") == 1 and f"Saved: '{final}'" in completed.stderr
    assert ".prism-" not in printed, "the temporary file's name reached the console"


def test_missing_file_fails_clearly(tmp_path):
    completed = run_render_script(tmp_path / "nope.blend", "--output", tmp_path / "x.png")
    assert completed.returncode != 0
    assert "nope.blend' does not exist" in completed.stderr


def test_scene_without_camera_fails_clearly(fresh_scene, tmp_path):
    add_plane("Floor", 2.0)
    path = tmp_path / "no_camera.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    completed = run_render_script(path, "--output", tmp_path / "x.png")
    assert completed.returncode != 0
    assert "has no active camera" in completed.stderr
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    "arguments, message",
    [
        (["--samples", "0"], "--samples must be at least 1"),
        (["--samples", "many"], "invalid int value: 'many'"),
        (["--bogus"], "unrecognized arguments: --bogus"),
    ],
)
def test_wrong_arguments_fail_clearly(lit_scene_file, tmp_path, arguments, message):
    completed = run_render_script(lit_scene_file, "--output", tmp_path / "x.png", *arguments)
    assert completed.returncode == 2
    assert message in completed.stderr


def test_wrong_output_format_fails_clearly(lit_scene_file, tmp_path):
    completed = run_render_script(lit_scene_file, "--output", tmp_path / "x.jpg")
    assert completed.returncode == 2
    assert "--output must end in .png or .exr" in completed.stderr


def _real_lens_scene_file(tmp_path, lens_model):
    add_plane("Floor", 6.0)
    camera = add_camera((0.0, -3.0, 1.0), (1.5, 0.0, 0.0), resolution=(16, 16))
    camera.data.prism.lens_model = lens_model
    camera.data.prism.lens_source = "BUNDLED"
    camera.data.prism.bundled_lens = "double_gauss_50mm"
    path = tmp_path / f"{lens_model.lower()}.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return path


def test_lens_diagram_option_writes_the_overlay_drawing(fresh_scene, tmp_path):
    path = _real_lens_scene_file(tmp_path, "REAL_LENS")
    diagram = tmp_path / "lens.png"
    completed = run_render_script(path, "--lens-diagram", diagram)
    assert completed.returncode == 0, completed.stderr
    image = bpy.data.images.load(str(diagram))
    width, height = image.size
    pixels = np.array(image.pixels[:]).reshape(height, width, 4)[..., :3]
    assert pixels.std() > 0.02, "the lens diagram is blank"
    reddish = (pixels[..., 0] > pixels[..., 2] + 0.2).sum()
    bluish = (pixels[..., 2] > pixels[..., 0] + 0.2).sum()
    assert reddish > 50 and bluish > 50, "ray fans are coloured by wavelength"


def test_lens_diagram_needs_a_real_lens(fresh_scene, tmp_path):
    path = _real_lens_scene_file(tmp_path, "PINHOLE")
    completed = run_render_script(path, "--lens-diagram", tmp_path / "lens.png")
    assert completed.returncode == 1
    assert "Prism: error:" in completed.stderr and "lens" in completed.stderr.lower()
    assert not (tmp_path / "lens.png").exists()
