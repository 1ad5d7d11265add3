"""The viewport's render thread outside Blender: coarse first, changes between passes, stop."""

import threading
import time
from dataclasses import replace

import numpy as np
import pytest

from engine.tracer.scene import Camera, Light, Material
from engine.viewport.progressive import THREAD_NAME, Change, ProgressiveRender
from tracer.tracer_scenes import look_at, make_scene, quad, settings

SIZE = (64, 48)


def _scene(card=(0.8, 0.1, 0.1)):
    camera = Camera("view", look_at((0.0, -4.0, 3.0), (0.0, 0.0, 0.3)), SIZE)
    parts = [(*quad((0, 0, 0), (3, 0, 0), (0, 3, 0)), 0), (*quad((0, 0, 0.5), (0.6, 0, 0), (0, 0.6, 0)), 1)]
    materials = [Material("floor", base_color=(0.5, 0.5, 0.5)), Material("card", base_color=card)]
    return make_scene(parts, materials, camera, [Light("lamp", "point", np.array([0.5, -0.5, 2.5]), power_w=400.0)])


def _until(predicate, timeout=60.0):
    end = time.perf_counter() + timeout
    while not predicate():
        assert time.perf_counter() < end, "timed out"
        time.sleep(0.005)


def _wait(render, condition, timeout=60.0):
    end = time.perf_counter() + timeout
    while time.perf_counter() < end:
        frame = render.frame
        if render.error or (frame is not None and condition(frame)):
            assert render.error is None, render.error
            return frame
        time.sleep(0.005)
    raise AssertionError(f"no such frame in {timeout} s (last: {render.frame}, {render.status})")


@pytest.fixture
def render():
    frames = []
    render = ProgressiveRender(on_frame=lambda: frames.append(render.frame))
    render.frames = frames
    yield render
    render.stop()
    assert not render.running


def _start(render, scene, samples=8):
    return render.update(Change(scene=scene, geometry=True, camera=scene.camera, settings=settings(threads=2),
                                samples=samples))


def test_first_image_is_coarse_and_one_sample_then_refines_to_the_target(render):
    scene = _scene()
    _start(render, scene)
    final = _wait(render, lambda f: f.divider == 1 and f.samples == 8)
    published = [f for f in render.frames if f is not None]
    first = published[0]
    assert (first.divider, first.samples, first.width, first.height) == (2, 1, 32, 24)
    assert first.rgba[..., 3].min() == 1.0 and first.rgba[..., :3].mean() > 0.01
    assert [f.divider for f in published][:2] == [2, 1]
    assert (final.width, final.height) == SIZE
    time.sleep(0.05)
    assert render.frame is final  # the target reached: the thread waits


def test_a_camera_move_restarts_at_once_and_a_colour_change_keeps_the_triangles(render):
    scene = _scene()
    _start(render, scene, samples=0)  # until stopped
    _wait(render, lambda f: f.divider == 1 and f.samples >= 4)
    renderer = render._renderer
    accel = renderer.tables.accel
    moved = replace(scene.camera, camera_to_world=look_at((2.0, -3.0, 3.0), (0.0, 0.0, 0.3)))
    number = render.update(Change(camera=moved))
    first = _wait(render, lambda f: f.change == number)
    assert first.samples == 1 and first.divider == 2
    green = _scene(card=(0.1, 0.8, 0.1))
    number = render.update(Change(scene=green))
    frame = _wait(render, lambda f: f.change == number and f.divider == 1 and f.samples >= 2)
    assert render._renderer is renderer and renderer.tables.accel is accel  # no new Embree scene
    assert renderer.scene.materials[1].base_color == (0.1, 0.8, 0.1)
    card = frame.rgba[..., :3].reshape(-1, 3)
    assert (card[:, 1] > 2 * card[:, 0] + 0.05).any()  # green pixels


def test_a_border_leaves_the_rest_transparent(render):
    scene = _scene()
    render.update(Change(scene=scene, geometry=True, camera=scene.camera, border=(8, 4, 40, 30),
                         settings=settings(threads=1), samples=2))
    frame = _wait(render, lambda f: f.divider == 1 and f.samples == 2)
    alpha = frame.rgba[::-1, :, 3]  # rows from the top
    assert alpha[4:30, 8:40].min() == 1.0 and alpha.sum() == 32 * 26


def test_bad_input_is_reported_and_the_next_change_recovers(render):
    scene = _scene()
    broken = replace(scene, materials=[scene.materials[0], Material("card", kind="dielectric", glass="NO-SUCH")])
    render.update(Change(scene=broken, geometry=True, camera=scene.camera, settings=settings(), samples=1))
    _until(lambda: render.error is not None)
    assert "NO-SUCH" in render.error and render.frame is None
    render.update(Change(scene=scene, geometry=True))
    _until(lambda: render.error is None)
    _wait(render, lambda f: f.divider == 1 and f.samples == 1)


def test_pause_and_stop_leave_no_thread(render):
    before = {t for t in threading.enumerate()}
    scene = _scene()
    _start(render, scene, samples=0)
    _wait(render, lambda f: f.divider == 1)
    render.pause(True)
    held, end = None, time.perf_counter() + 30.0
    while held is not render.frame:  # the pass in flight finishes, then nothing more comes
        assert time.perf_counter() < end
        held = render.frame
        time.sleep(0.3)
    samples = held.samples
    render.pause(False)
    _wait(render, lambda f: f.samples > samples)
    started = time.perf_counter()
    render.stop()
    assert time.perf_counter() - started < 5.0
    assert not render.running
    left = [t for t in threading.enumerate() if t not in before and t.is_alive()]
    assert not left, left
    assert all(t.name != THREAD_NAME for t in threading.enumerate())
