"""The rendered viewport's session with a real evaluated depsgraph and region, headless: the first
image, navigation, incremental edits, settings, errors and a clean end."""

from __future__ import annotations

import gc
import importlib
import threading
import time

import bpy
import numpy as np
import pytest
from helpers.bpy_scenes import build_lit_card_scene
from helpers.viewport import StubEngine, camera_context, view_context, wait_for_frame
from mathutils import Matrix

REGION = (96, 64)


def _module(addon, name):
    return importlib.import_module(f"{addon.__name__}.engine.viewport.{name}")


def _prism_threads():
    return [t for t in threading.enumerate() if t.name == "Prism viewport" and t.is_alive()]


@pytest.fixture
def viewport(prism_addon, fresh_scene):
    """(session, engine, context): the lit card scene in a 96 x 64 region seen from its camera's
    place (a free view); every depsgraph update reaches ``view_update`` as in Blender."""
    build_lit_card_scene(resolution=REGION)
    fresh_scene.prism.preview_samples = 16
    fresh_scene.prism.threads = 2
    engine = StubEngine()
    session = engine.session = _module(prism_addon, "session").session_of(engine)
    context = camera_context(fresh_scene, REGION, camera_view=False)

    def on_update(scene, depsgraph):
        session.view_update(context, depsgraph)

    bpy.app.handlers.depsgraph_update_post.append(on_update)
    session.view_update(context, bpy.context.evaluated_depsgraph_get())
    yield session, engine, context
    bpy.app.handlers.depsgraph_update_post.remove(on_update)
    session.stop()
    assert not session.render.running


def _update():
    """Evaluate the depsgraph as Blender does after an edit (``view_update`` runs in the handler)."""
    bpy.context.view_layer.update()


def _card_pixels(frame):
    """RGB of the pixels the red/green card covers (middle of the image, rows from the top)."""
    rgb = frame.rgba[::-1, :, :3]
    h, w = rgb.shape[:2]
    return rgb[h // 3: 2 * h // 3, w // 3: 2 * w // 3].reshape(-1, 3)


def test_first_image_is_one_coarse_sample_then_full_resolution(viewport):
    session, engine, _ = viewport
    wait_for_frame(session, lambda f: f.divider == 1)
    first, second, full = [f for f in engine.frames if f is not None][:3]
    assert first.samples == 1 and first.divider == 4 and (first.width, first.height) == (24, 16)
    assert second.samples == 1 and second.divider == 2 and (second.width, second.height) == (48, 32)
    assert full.divider == 1 and (full.width, full.height) == REGION and full.samples <= 16
    assert np.isfinite(full.rgba).all() and full.rgba[..., 3].min() == 1.0
    done = wait_for_frame(session, lambda f: f.samples == 16)
    assert engine.redraws >= 3  # the render thread asked Blender for a redraw per frame
    status = session.status()
    assert status.startswith("Prism | Pass") and "16/16 spp" in status
    time.sleep(0.1)
    assert session.render.frame is done  # the viewport's sample target reached: nothing more runs


def test_navigation_restarts_the_image_at_once(viewport):
    session, _, context = viewport
    before = wait_for_frame(session, lambda f: f.divider == 1 and f.samples >= 2)
    renderer = session.render._renderer
    accel = renderer.tables.accel
    context.region_data.view_matrix = Matrix.Rotation(0.3, 4, "Z") @ context.region_data.view_matrix
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())
    wait_for_frame(session, lambda f: f.change > before.change)
    engine = viewport[1]
    after = next(f for f in engine.frames if f is not None and f.change > before.change)
    assert after.samples == 1 and after.divider == 4
    moved = wait_for_frame(session, lambda f: f.change > before.change and f.divider == 1)
    assert session.render._renderer is renderer and renderer.tables.accel is accel  # the triangles stay
    assert np.abs(moved.rgba - before.rgba).mean() > 0.01
    # a redraw of the same view changes nothing
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())
    time.sleep(0.05)
    assert session.render.frame.change == moved.change


def test_material_colour_change_updates_shading_without_reading_a_mesh(viewport):
    session, _, _ = viewport
    red = wait_for_frame(session, lambda f: f.divider == 1)
    card = _card_pixels(red).mean(axis=0)
    assert card[0] > 2 * card[1]
    reads, renderer = session.sync.mesh_reads, session.render._renderer
    accel, geometry = renderer.tables.accel, renderer.tables.geometry
    principled = bpy.data.materials["Card material"].node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (0.1, 0.8, 0.1, 1.0)
    _update()
    green = wait_for_frame(session, lambda f: f.change > red.change and f.divider == 1)
    card = _card_pixels(green).mean(axis=0)
    assert card[1] > 2 * card[0]
    assert session.sync.mesh_reads == reads  # no mesh exported again
    assert renderer.tables.accel is accel and renderer.tables.geometry is geometry  # nor a new Embree scene


def test_moves_place_again_and_edits_read_only_the_edited_mesh(viewport):
    session, _, _ = viewport
    first = wait_for_frame(session, lambda f: f.divider == 1)
    reads = session.sync.mesh_reads
    bpy.data.objects["Card"].location.x += 0.8
    _update()
    moved = wait_for_frame(session, lambda f: f.change > first.change and f.divider == 1)
    assert session.sync.mesh_reads == reads  # placed again from the kept mesh
    mesh = bpy.data.objects["Card"].data
    mesh.vertices[0].co.z += 0.3
    mesh.update()
    _update()
    wait_for_frame(session, lambda f: f.change > moved.change and f.divider == 1)
    assert session.sync.mesh_reads == reads + 1  # the card only, not the floor


def test_light_edits_and_settings_reach_the_render(viewport):
    session, _, context = viewport
    first = wait_for_frame(session, lambda f: f.divider == 1)
    renderer = session.render._renderer
    accel = renderer.tables.accel
    bpy.data.lights["Bulb"].energy = 30.0  # a tenth
    _update()
    dim = wait_for_frame(session, lambda f: f.change > first.change and f.divider == 1)
    assert renderer.tables.accel is accel
    assert dim.rgba[..., :3].mean() < 0.3 * first.rgba[..., :3].mean()
    scene = bpy.context.scene
    scene.prism.preview_max_bounces = 1
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())  # a settings change only redraws
    wait_for_frame(session, lambda f: f.change > dim.change)
    assert renderer.settings.max_bounces == 1 and renderer.tables.accel is accel


def test_pause_holds_the_image_until_resumed(viewport):
    session, _, context = viewport
    scene = bpy.context.scene
    scene.prism.preview_samples = 0  # until stopped
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())
    wait_for_frame(session, lambda f: f.divider == 1 and f.samples >= 2)
    scene.prism.preview_pause = True
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())
    assert session.status().endswith("Paused")
    held, end = None, time.perf_counter() + 30.0
    while held is not session.render.frame:  # the pass in flight finishes, then nothing more comes
        assert time.perf_counter() < end
        held = session.render.frame
        time.sleep(0.5)
    assert session.render.frame is held
    scene.prism.preview_pause = False
    session.sync_view(context, bpy.context.evaluated_depsgraph_get())
    wait_for_frame(session, lambda f: f.samples > held.samples)


def test_a_camera_view_through_a_panoramic_camera_says_so(viewport):
    session, _, _ = viewport
    wait_for_frame(session)
    scene = bpy.context.scene
    scene.camera.data.type = "PANO"
    scene.camera.data.panorama_type = "EQUIRECTANGULAR"
    _update()
    session.sync_view(camera_context(scene, REGION, camera_view=True), bpy.context.evaluated_depsgraph_get())
    assert session.error is not None and "panoramic camera 'Camera'" in session.status()


def test_the_viewport_region_border_is_honoured(viewport):
    session, _, context = viewport
    border_context = camera_context(bpy.context.scene, REGION, camera_view=False, region_border=(0.25, 0.5, 0.75, 1.0))
    session.sync_view(border_context, bpy.context.evaluated_depsgraph_get())
    frame = wait_for_frame(session, lambda f: f.divider == 1 and f.rgba[..., 3].min() == 0.0)
    alpha = frame.rgba[::-1, :, 3]  # rows from the top
    assert alpha[0:32, 24:72].min() == 1.0 and alpha.sum() == 48 * 32


def test_freeing_the_engine_stops_the_thread(prism_addon, fresh_scene):
    build_lit_card_scene(resolution=REGION)
    before = set(threading.enumerate())
    engine = StubEngine()
    session = _module(prism_addon, "session").session_of(engine)
    session.view_update(camera_context(fresh_scene, REGION, camera_view=False), bpy.context.evaluated_depsgraph_get())
    wait_for_frame(session)
    render = session.render
    del engine, session
    gc.collect()
    assert not render.running
    left = [t for t in threading.enumerate() if t not in before and t.is_alive()]
    assert not left, left


def test_unregistering_stops_every_viewport(prism_addon, fresh_scene):
    build_lit_card_scene(resolution=REGION)
    engine = StubEngine()
    session = _module(prism_addon, "session").session_of(engine)
    session.view_update(camera_context(fresh_scene, REGION, camera_view=False), bpy.context.evaluated_depsgraph_get())
    wait_for_frame(session)
    prism_addon.unregister()
    try:
        assert not session.render.running and not _prism_threads()
    finally:
        prism_addon.register()
