"""Driving a ``ViewportSession`` headless: a stand-in for the 3D viewport's context (region size,
view and window matrices, the space's render border) and a stand-in engine that counts redraws."""

from __future__ import annotations

import time
from types import SimpleNamespace

import bpy


class StubEngine:
    """What the session calls on its engine outside drawing: ``tag_redraw`` (from the render thread,
    right after each new frame: ``frames`` lists them all) and ``update_stats``."""

    def __init__(self):
        self.redraws = 0
        self.frames = []
        self.session = None
        self.stats: list[str] = []

    def tag_redraw(self):
        self.redraws += 1
        if self.session is not None:
            self.frames.append(self.session.render.frame)

    def update_stats(self, stats, info):
        self.stats.append(info)


def view_context(view_matrix, window_matrix, size, camera_view=False, region_border=None, clip_end=1000.0):
    """A ``context`` with what ``view_update`` / ``view_draw`` read of a 3D viewport region."""
    width, height = size
    region_data = SimpleNamespace(
        view_matrix=view_matrix.copy(), window_matrix=window_matrix.copy(),
        perspective_matrix=window_matrix @ view_matrix, view_perspective="CAMERA" if camera_view else "PERSP",
        is_perspective=window_matrix[3][3] == 0.0,  # a perspective projection's last row is (0, 0, -1, 0)
    )
    x0, y0, x1, y1 = region_border or (0.0, 0.0, 1.0, 1.0)
    space = SimpleNamespace(use_render_border=region_border is not None, render_border_min_x=x0,
                            render_border_min_y=y0, render_border_max_x=x1, render_border_max_y=y1,
                            clip_end=clip_end)
    return SimpleNamespace(region=SimpleNamespace(width=width, height=height), region_data=region_data,
                           space_data=space)


def camera_context(scene, size, camera_view=True, **kw):
    """The region looking through (or, ``camera_view=False``, from where) the scene camera, its frame
    filling a region of ``size``."""
    camera = scene.camera
    depsgraph = bpy.context.evaluated_depsgraph_get()
    window = camera.calc_matrix_camera(depsgraph, x=size[0], y=size[1])
    return view_context(camera.matrix_world.inverted(), window, size, camera_view, **kw)


def wait_for_frame(session, condition=lambda frame: True, timeout=90.0):
    """The first published frame meeting ``condition`` (fails on a render error or a time-out)."""
    end = time.perf_counter() + timeout
    while time.perf_counter() < end:
        assert session.error is None, session.error
        frame = session.render.frame
        if frame is not None and condition(frame):
            return frame
        time.sleep(0.01)
    raise AssertionError(f"no such frame within {timeout} s: {session.status()}")
