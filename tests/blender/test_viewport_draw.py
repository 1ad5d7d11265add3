"""What the rendered viewport puts on screen: ``view_draw`` on a real engine drawing offscreen on the
headless GPU, and the camera view (real lens included) against the final render, both through the
scene's view transform."""

from __future__ import annotations

import importlib
import threading

import bpy
import numpy as np
import pytest
from helpers.bpy_scenes import build_lit_card_scene, render_linear_rgb
from helpers.viewport import StubEngine, camera_context, view_context, wait_for_frame
from mathutils import Matrix

REGION = (48, 32)


def _display_encoded(scene, rgb_bottom_up: np.ndarray, tmp_path) -> np.ndarray:
    """Scene-linear RGB [H, W, 3] (first row at the bottom) through the scene's display device, view
    transform, look and exposure, as Blender shows it: saved through them as a 16-bit PNG, read back."""
    height, width = rgb_bottom_up.shape[:2]
    image = bpy.data.images.new("display check", width, height, float_buffer=True)
    path = tmp_path / f"display_{len(list(tmp_path.iterdir()))}.png"
    try:
        rgba = np.ones((height, width, 4), np.float32)
        rgba[..., :3] = rgb_bottom_up
        image.pixels.foreach_set(rgba.ravel())
        settings = scene.render.image_settings
        settings.file_format, settings.color_mode, settings.color_depth = "PNG", "RGB", "16"
        image.save_render(str(path), scene=scene)
    finally:
        bpy.data.images.remove(image)
    loaded = bpy.data.images.load(str(path))
    try:
        pixels = np.empty(width * height * 4, np.float32)
        loaded.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(loaded)
    return pixels.reshape(height, width, 4)[..., :3]


def _pixel_space_projection(width, height):
    return Matrix(((2.0 / width, 0, 0, -1.0), (0, 2.0 / height, 0, -1.0), (0, 0, -1.0, 0), (0, 0, 0, 1.0)))


def _draw_in_a_real_engine(addon, monkeypatch, context, samples, then=None) -> dict:
    """Run a viewport session in an engine Blender made (for a render: its
    ``bind_display_space_shader`` is real), wait for ``samples`` at full resolution, call
    ``view_draw`` into a float offscreen the region's size, then ``then(depsgraph)`` with the
    region's view matrices (Blender's POST_VIEW overlays). Returns the session's ``render`` and
    ``frame``, the drawn ``pixels`` (rows from the bottom) and ``then``'s result."""
    seen = {}
    width, height = context.region.width, context.region.height

    def render(self, depsgraph):
        import gpu

        self.view_update(context, depsgraph)
        seen["render"] = self._prism_viewport.render
        seen["frame"] = wait_for_frame(self._prism_viewport, lambda f: f.divider == 1 and f.samples == samples)
        offscreen = gpu.types.GPUOffScreen(width, height, format="RGBA32F")
        try:
            with offscreen.bind():
                framebuffer = gpu.state.active_framebuffer_get()
                framebuffer.clear(color=(0.0, 0.0, 0.0, 0.0))
                with gpu.matrix.push_pop(), gpu.matrix.push_pop_projection():
                    gpu.matrix.load_matrix(Matrix.Identity(4))
                    gpu.matrix.load_projection_matrix(_pixel_space_projection(width, height))
                    self.view_draw(context, depsgraph)
                    if then is not None:
                        gpu.matrix.load_projection_matrix(context.region_data.window_matrix)
                        gpu.matrix.load_matrix(context.region_data.view_matrix)
                        seen["then"] = then(depsgraph)
                buffer = framebuffer.read_color(0, 0, width, height, 4, 0, "FLOAT")
        finally:
            offscreen.free()
        buffer.dimensions = width * height * 4
        seen["pixels"] = np.array(buffer, dtype=np.float32).reshape(height, width, 4)
        self.end_result(self.begin_result(0, 0, 4, 4))

    monkeypatch.setattr(addon.engine.render.render_engine.PrismRenderEngine, "render", render)
    scene = bpy.context.scene
    resolution = scene.render.resolution_x, scene.render.resolution_y
    scene.render.resolution_x = scene.render.resolution_y = 4
    try:
        bpy.ops.render.render()
    finally:
        scene.render.resolution_x, scene.render.resolution_y = resolution
    return seen


@pytest.fixture
def card_scene(fresh_scene):
    build_lit_card_scene(resolution=REGION)
    prism = fresh_scene.prism
    prism.preview_samples, prism.threads = 8, 2
    prism.preview_max_bounces = prism.max_bounces  # the viewport traces what the final render traces
    view = fresh_scene.view_settings
    view.view_transform, view.exposure = "AgX", 0.7
    return fresh_scene


def test_view_draw_shows_the_session_image_through_the_display_shader(prism_addon, card_scene, gpu_ready,
                                                                      monkeypatch, tmp_path):
    """``view_draw`` of a real engine (one Blender made for a render: ``bind_display_space_shader``
    is real) into a float offscreen the size of the region: every pixel is the session's
    scene-linear value (HDR kept), which Blender's view transform then maps as the final render's."""
    seen = _draw_in_a_real_engine(prism_addon, monkeypatch, camera_context(card_scene, REGION), samples=8)
    frame, drawn = seen["frame"], seen["pixels"]
    assert frame.rgba[..., :3].max() > 1.0  # highlights above 1 reach the view transform
    np.testing.assert_allclose(drawn, frame.rgba, rtol=2e-3, atol=1e-4)  # half floats
    assert not seen["render"].running  # the render's engine is gone: so is the thread
    assert not [t for t in threading.enumerate() if t.name == "Prism viewport"]
    scene = bpy.context.scene
    np.testing.assert_allclose(_display_encoded(scene, drawn[..., :3], tmp_path),
                               _display_encoded(scene, frame.rgba[..., :3], tmp_path), atol=2e-3)


@pytest.mark.parametrize("lens_model", ["PINHOLE", "REAL_LENS", "ORTHOGRAPHIC"])
def test_camera_view_shows_the_final_render(prism_addon, card_scene, tmp_path, lens_model):
    """Looking through the camera, its frame filling the region: the viewport traces the final
    render's rays (the real lens and an orthographic camera too) and, through AgX at +0.7 EV, shows
    its picture."""
    camera = card_scene.camera.data
    if lens_model == "ORTHOGRAPHIC":
        camera.type, camera.ortho_scale = "ORTHO", 3.0
    else:
        camera.prism.lens_model = lens_model
    if lens_model == "REAL_LENS":
        camera.prism.lens_source, camera.prism.bundled_lens = "BUNDLED", "double_gauss_50mm"
        camera.dof.focus_distance, camera.dof.aperture_fstop = 3.9, 4.0
    final = render_linear_rgb(card_scene, samples=8, seed=0)
    engine = StubEngine()  # kept: the session ends with its engine
    session = importlib.import_module(f"{prism_addon.__name__}.engine.viewport.session").session_of(engine)
    try:
        session.view_update(camera_context(card_scene, REGION), bpy.context.evaluated_depsgraph_get())
        frame = wait_for_frame(session, lambda f: f.divider == 1 and f.samples == 8)
        if lens_model == "REAL_LENS":
            assert "real lens 'Double Gauss" in session.status()
    finally:
        session.stop()
    viewport = frame.rgba[..., :3]
    # the same seed, samples and bounces; only rounding (the film from Blender's projection) differs
    assert np.abs(viewport - final[::-1]).mean() < 1e-4 * final.mean()
    shown = _display_encoded(card_scene, viewport, tmp_path)
    expected = _display_encoded(card_scene, final[::-1], tmp_path)
    assert np.abs(shown - expected).max() < 1e-3


@pytest.mark.parametrize("forward_m", [0.0, 3.5])
def test_an_orthographic_free_view_renders_the_orthographic_cameras_picture(prism_addon, card_scene, forward_m):
    """A free orthographic view where the orthographic camera stands, or moved 3.5 m along its axis
    past the card: Blender draws such a view from clip_end / 2 behind its centre, so both show the
    camera's final render (the same rays but for where they start)."""
    camera = card_scene.camera.data
    camera.type, camera.ortho_scale = "ORTHO", 3.0
    final = render_linear_rgb(card_scene, samples=8, seed=0)
    engine = StubEngine()
    session = importlib.import_module(f"{prism_addon.__name__}.engine.viewport.session").session_of(engine)
    context = camera_context(card_scene, REGION, camera_view=False)
    view = context.region_data
    view.view_matrix = Matrix.Translation((0.0, 0.0, forward_m)) @ view.view_matrix
    assert not view.is_perspective
    try:
        session.view_update(context, bpy.context.evaluated_depsgraph_get())
        frame = wait_for_frame(session, lambda f: f.divider == 1 and f.samples == 8)
    finally:
        session.stop()
    assert np.abs(frame.rgba[..., :3] - final[::-1]).mean() < 1e-4 * final.mean()


def _perspective(width, height, fov_y=0.8, near=0.1, far=100.0):
    f = 1.0 / np.tan(fov_y / 2)
    return Matrix(((f * height / width, 0, 0, 0), (0, f, 0, 0),
                   (0, 0, (far + near) / (near - far), 2 * far * near / (near - far)), (0, 0, -1, 0)))


def test_the_lens_overlay_draws_over_the_rendered_viewport(prism_addon, card_scene, gpu_ready, monkeypatch):
    """A free view beside the real-lens camera: ``view_draw`` puts the render in the region, then the
    overlay's POST_VIEW drawing (as Blender calls it next) adds the ray fan on top of it."""
    from mathutils import Vector

    overlay = prism_addon.ui.lens_overlay_draw
    camera = card_scene.camera
    camera.data.prism.lens_model, camera.data.prism.lens_source = "REAL_LENS", "BUNDLED"
    camera.data.prism.bundled_lens = "double_gauss_50mm"
    settings = card_scene.prism.lens_overlay
    settings.wavelength_source, settings.custom_wavelengths_nm = "CUSTOM", "450"
    card_scene.prism.preview_samples = 2
    bpy.context.view_layer.update()
    size = width, height = 160, 120
    side = camera.matrix_world.to_3x3() @ Vector((1.0, 0.0, 0.0))
    ahead = camera.matrix_world.translation + camera.matrix_world.to_3x3() @ Vector((0.0, 0.0, -0.5))
    eye = ahead + 2.5 * side
    view = Matrix.Translation(eye) @ (ahead - eye).to_track_quat("-Z", "Z").to_matrix().to_4x4()
    view = view.inverted()
    context = view_context(view, _perspective(width, height), size)
    seen = _draw_in_a_real_engine(prism_addon, monkeypatch, context, samples=2,
                                  then=lambda depsgraph: overlay.draw_at_camera(depsgraph.scene, size, 1.0))
    overlay.remove_handlers()
    assert seen["then"]
    frame, pixels = seen["frame"].rgba, seen["pixels"]
    changed = np.abs(pixels[..., :3] - frame[..., :3]).max(axis=-1) > 0.05
    assert 50 < changed.sum() < 0.2 * width * height  # the fan and the lens, over a small part
    blue = changed & (pixels[..., 2] > pixels[..., 0] + 0.3)
    assert blue.sum() > 20  # 450 nm rays
    near = changed.copy()  # the lines' smoothed edges fade out over a pixel or two
    for axis in (0, 1):
        for step in (-2, -1, 1, 2):
            near |= np.roll(changed, step, axis=axis)
    untouched = ~near
    assert untouched.mean() > 0.8
    np.testing.assert_allclose(pixels[untouched], frame[untouched], rtol=2e-3, atol=1e-4)  # the render elsewhere
