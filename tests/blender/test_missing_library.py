"""A linked library Blender cannot find: the render names the library's file and the objects it leaves
out (a warning when something else renders, the error when nothing is left to see)."""

from __future__ import annotations

import bpy

from helpers.batch import run_batch, run_batch_stderr
from helpers.bpy_scenes import add_camera, add_plane, add_point_light


def _shot_linking_a_lost_library(folder, with_floor: bool):
    """Saves ``props.blend`` (a cube 'Rock') and ``shot.blend`` linking the rock, then moves the library
    away and opens the shot: Blender keeps 'Rock' as an empty placeholder."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    bpy.ops.mesh.primitive_cube_add()
    bpy.context.object.name = "Rock"
    bpy.ops.wm.save_as_mainfile(filepath=str(folder / "props.blend"))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    scene.render.engine = "PRISM"
    with bpy.data.libraries.load(str(folder / "props.blend"), link=True) as (_, linked):
        linked.objects = ["Rock"]
    scene.collection.objects.link(linked.objects[0])
    if with_floor:
        add_plane("Floor", 8.0, location=(0.0, 0.0, -1.0))
    add_point_light("Bulb", 300.0, (0.0, -2.0, 4.0))
    add_camera((0.0, -8.0, 3.0), (1.2, 0.0, 0.0), resolution=(16, 12))
    bpy.ops.wm.save_as_mainfile(filepath=str(folder / "shot.blend"))
    (folder / "props.blend").rename(folder / "props_moved.blend")
    bpy.ops.wm.open_mainfile(filepath=str(folder / "shot.blend"))
    return (f"the linked library 'props.blend' is missing (no file at {folder / 'props.blend'}), so object "
            "'Rock' from it is not rendered: relocate it (Outliner ▸ Blender File ▸ right-click the library ▸ "
            "Relocate) or restore the file.")


def test_missing_library_with_nothing_else_names_the_file(prism_addon, tmp_path, capsys, bad_input):
    sentence = _shot_linking_a_lost_library(tmp_path, with_floor=False)
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status != 0
    assert line == f"Prism: error: Scene 'Scene' has no visible geometry: {sentence}"
    bad_input("a scene whose only object comes from a missing linked library", status, line)


def test_missing_library_beside_other_geometry_warns_once(prism_addon, tmp_path, capsys, bad_input):
    sentence = _shot_linking_a_lost_library(tmp_path, with_floor=True)
    status, stderr = run_batch_stderr(capsys, "--samples", 1, "--output", tmp_path / "x.png")
    assert status == 0 and (tmp_path / "x.png").is_file(), stderr
    shown = f"Prism: warning: Scene 'Scene': {sentence}"
    assert stderr.count(shown) == 1, stderr
    bad_input("a scene with an object from a missing linked library (a warning; the rest renders)", status, shown)
