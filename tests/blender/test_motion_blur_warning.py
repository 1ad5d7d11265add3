"""Render ▸ Motion Blur on: until Prism has motion blur, one warning per render names the setting and
says the image is rendered without it, and the image is the one rendered with the setting off."""

from __future__ import annotations

import bpy
import numpy as np

from helpers.batch import run_batch_stderr
from helpers.bpy_scenes import add_camera, add_plane, add_point_light, image_pixels


def test_motion_blur_warns_once_and_renders_sharp(prism_addon, fresh_scene, tmp_path, capsys, bad_input):
    """A card flying across the frame between frames 1 and 2, rendered at frame 1 with Motion Blur on and
    off: one warning with it on, none with it off, and the same pixels (same seed)."""
    card = add_plane("Card", 1.0, color=(0.8, 0.4, 0.2))
    add_plane("Floor", 8.0, location=(0.0, 0.0, -0.5))
    add_point_light("Bulb", 200.0, (0.0, 0.0, 3.0))
    add_camera((0.0, 0.0, 6.0), (0.0, 0.0, 0.0), resolution=(24, 16))
    card.location = (-1.0, 0.0, 0.0)
    card.keyframe_insert("location", frame=1)
    card.location = (1.0, 0.0, 0.0)
    card.keyframe_insert("location", frame=2)
    fresh_scene.frame_set(1)
    shown = ("Prism: warning: Scene 'Scene': Render Properties ▸ Motion Blur is on, but Prism has no motion blur "
             "yet: the image is rendered without motion blur, everything sharp where it stands at frame 1.")
    images = {}
    for blur in (True, False):
        fresh_scene.render.use_motion_blur = blur
        path = tmp_path / f"blur_{blur}.exr"
        status, stderr = run_batch_stderr(capsys, "--samples", 4, "--seed", 3, "--output", path)
        assert status == 0, stderr
        assert stderr.count(shown) == (1 if blur else 0), stderr
        images[blur] = image_pixels(path)
    assert np.array_equal(images[True], images[False])
    assert images[True][..., :3].mean() > 0.01  # something was rendered
    bad_input("Render ▸ Motion Blur on (a warning; rendered sharp)", 0, shown)
