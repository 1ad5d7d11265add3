"""The lens overlay in Blender: real offscreen drawing, handler bookkeeping, background
safety, the settings cache and the PNG export."""

import importlib
import math

import bpy
import numpy as np
import pytest
from helpers.bpy_scenes import add_plane, add_point_light

SINGLET_DAT = """# test singlet: stop, then a biconvex N-BK7 lens
# radius  thickness  index  aperture
0       2.0   1       8.0
50.0    3.0   1.5168  12.0
-50.0   45.0  1       12.0
"""


@pytest.fixture
def overlay(prism_addon):
    draw = importlib.import_module(f"{prism_addon.__name__}.ui.lens_overlay_draw")
    yield draw
    draw.remove_handlers()


@pytest.fixture
def lens_scene(fresh_scene, tmp_path):
    """Active camera with a real lens read from a small singlet file."""
    path = tmp_path / "singlet.dat"
    path.write_text(SINGLET_DAT)
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    fresh_scene.collection.objects.link(camera)
    fresh_scene.camera = camera
    fresh_scene.render.resolution_x, fresh_scene.render.resolution_y = 24, 16
    camera.data.prism.lens_model = "REAL_LENS"
    camera.data.prism.lens_source = "FILE"
    camera.data.prism.lens_file = str(path)
    camera.data.dof.focus_distance = 10.0
    camera.data.dof.aperture_fstop = 8.0
    return fresh_scene


def _single_wavelength_diagram(addon, wavelength_nm):
    fan, media, system = (importlib.import_module(f"{addon.__name__}.engine.tracer.lens.{name}") for name in ("fan", "media", "system"))
    glass = media.FunctionMedium(lambda wl: 1.5046 + 4200.0 / wl**2, "cauchy")
    lens = system.LensSystem(
        (
            system.Surface(60.0, 4.0, 20.0, glass),
            system.Surface(-60.0, 2.0, 20.0, media.AIR),
            system.Surface(math.inf, 55.0, 14.0, media.AIR, is_stop=True),
        ),
        name="singlet",
    )
    return fan.lens_diagram(lens, [wavelength_nm], n_rays=9, sensor_half_height_mm=8.0)


def _pixel_of(matrix, z_mm, y_mm):
    x, y = (matrix[0][2] * z_mm + matrix[0][3], matrix[1][1] * y_mm + matrix[1][3])
    return int(round(y)), int(round(x))


@pytest.mark.parametrize("wavelength_nm, channel", [(450.0, 2), (650.0, 0)])
def test_offscreen_drawing_puts_wavelength_colours_along_the_ray_paths(prism_addon, gpu_ready, wavelength_nm, channel):
    export = importlib.import_module(f"{prism_addon.__name__}.ui.lens_overlay_export")
    diagram = _single_wavelength_diagram(prism_addon, wavelength_nm)
    width, height = 480, 240
    pixels = export.render_diagram_pixels(diagram, width, height)
    matrix, _ = export.diagram_layout(diagram, width, height)
    fan = diagram.fans[0]
    background = np.array(export.BACKGROUND_RGBA[:3])
    checked = faded = 0
    for ray in range(len(fan.fate)):
        # the incoming segment and, for reached rays, the last one (rear surface to sensor):
        # both in open air, away from the element outlines
        for k in {0, fan.vertex_count[ray] - 2} if fan.reached[ray] else {0}:
            a, b = fan.points_mm[ray, k], fan.points_mm[ray, k + 1]
            if abs(a[1]) < 1.0 and abs(b[1]) < 1.0:
                continue  # the axial ray lies on the drawn axis line
            mid = 0.5 * (a + b)
            row, col = _pixel_of(matrix, mid[2], mid[1])
            patch = pixels[row - 1 : row + 2, col - 1 : col + 2, :3].reshape(-1, 3)
            rgb = patch[np.argmax(patch.sum(axis=1))]
            others = max(np.delete(rgb, channel))
            if fan.reached[ray]:
                assert rgb[channel] > 0.6 and rgb[channel] > 2.0 * others, (ray, k, rgb)
                checked += 1
            else:  # blocked rays are drawn faded (alpha 0.25) in the same hue
                assert 0.15 < rgb[channel] < 0.5 and rgb[channel] > 1.5 * others, (ray, k, rgb)
                faded += 1
    assert checked >= 8 and faded >= 2
    # far from every ray (upper left corner of the cross-section area) only background
    row, col = _pixel_of(matrix, diagram.bounds_mm[0] + 1.0, 0.95 * diagram.bounds_mm[2])
    np.testing.assert_allclose(pixels[row, col, :3], background, atol=0.02)


def test_lens_maps_to_the_camera_minus_z_axis(prism_addon, lens_scene, overlay):
    from mathutils import Vector

    diagram, message = overlay.scene_diagram(lens_scene)
    assert diagram is not None, message
    camera = lens_scene.camera
    camera.location = (1.0, 2.0, 3.0)
    camera.rotation_euler = (0.3, 0.0, 1.0)
    camera.data.display_size = 0.5
    bpy.context.view_layer.update()
    to_world = camera.matrix_world @ overlay.lens_to_camera_matrix(diagram, 0.5)
    sensor = to_world @ Vector((0.0, 0.0, diagram.sensor_z_mm))
    front = to_world @ Vector((0.0, 0.0, 0.0))
    up = to_world @ Vector((0.0, 10.0, diagram.sensor_z_mm)) - sensor
    axis = camera.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))
    assert (sensor - camera.matrix_world.translation).length < 1e-6
    assert (front - sensor - 0.5 * axis).length < 1e-6
    assert up.normalized().dot(camera.matrix_world.to_3x3() @ Vector((0.0, 1.0, 0.0))) > 0.999999


def test_toggle_twice_leaves_no_handler(prism_addon, lens_scene, overlay, monkeypatch):
    monkeypatch.setattr(overlay, "_in_background", lambda: False)  # as in the UI
    settings = lens_scene.prism.lens_overlay
    assert not overlay.handlers_active()
    assert bpy.ops.prism.toggle_lens_overlay() == {"FINISHED"}
    assert settings.enabled and overlay.handlers_active() and set(overlay._handles) == {"view", "pixel"}
    bpy.ops.prism.toggle_lens_overlay()
    assert not settings.enabled and not overlay.handlers_active() and not overlay._handles
    bpy.ops.prism.toggle_lens_overlay()
    prism_addon.ui.unregister()  # unregistering removes the handlers too
    assert not overlay.handlers_active()
    prism_addon.ui.register()


def test_background_register_toggle_and_render_never_touch_gpu(prism_addon, lens_scene, overlay, monkeypatch):
    import gpu
    import gpu_extras.batch

    assert bpy.app.background
    calls = []

    def forbidden(*args, **kwargs):
        calls.append(args)
        raise AssertionError("gpu used in background mode")

    for module, name in [
        (gpu.shader, "from_builtin"), (gpu.types, "GPUOffScreen"), (gpu.state, "blend_set"),
        (gpu.matrix, "push_pop"), (gpu.matrix, "multiply_matrix"), (gpu_extras.batch, "batch_for_shader"),
    ]:
        monkeypatch.setattr(module, name, forbidden)
    monkeypatch.setattr(bpy.types.SpaceView3D, "draw_handler_add", forbidden, raising=False)
    prism_addon.unregister()
    prism_addon.register()
    scene = bpy.context.scene
    scene.camera.data.prism.lens_model = "PINHOLE"
    assert bpy.ops.prism.toggle_lens_overlay() == {"FINISHED"}
    assert scene.prism.lens_overlay.enabled and not overlay.handlers_active()
    add_plane("Floor", 4.0)
    add_point_light("Bulb", 100.0, (0.0, 0.0, 2.0))
    scene.camera.location = (0.0, 0.0, 3.0)
    scene.prism.samples = 1
    bpy.ops.render.render()
    assert calls == []


def test_diagram_is_cached_until_an_input_changes(prism_addon, lens_scene, overlay):
    first, message = overlay.scene_diagram(lens_scene)
    assert first is not None, message
    assert overlay.scene_diagram(lens_scene)[0] is first
    lens_scene.camera.data.dof.aperture_fstop = 4.0
    second = overlay.scene_diagram(lens_scene)[0]
    assert second is not first and second.f_number < first.f_number
    lens_scene.prism.lens_overlay.wavelength_source = "CUSTOM"
    lens_scene.prism.lens_overlay.custom_wavelengths_nm = "480, 520"
    third = overlay.scene_diagram(lens_scene)[0]
    assert third.wavelengths_nm == (480.0, 520.0) and len(third.spots) == 2
    lens_scene.prism.lens_overlay.custom_wavelengths_nm = "480, blue"
    diagram, message = overlay.scene_diagram(lens_scene)
    assert diagram is None and "blue" in message
    lens_scene.camera.data.prism.lens_model = "PINHOLE"
    diagram, message = overlay.scene_diagram(lens_scene)
    assert diagram is None and "Real lens" in message


def test_export_operator_writes_the_bundled_double_gauss_png(prism_addon, lens_scene, gpu_ready, tmp_path):
    lens_scene.camera.data.prism.lens_source = "BUNDLED"
    lens_scene.camera.data.prism.bundled_lens = "double_gauss_50mm"
    path = tmp_path / "diagram.png"
    assert bpy.ops.prism.export_lens_diagram(filepath=str(path), width=300, height=150) == {"FINISHED"}
    image = bpy.data.images.load(str(path))
    try:
        assert tuple(image.size) == (300, 150)
        pixels = np.empty(300 * 150 * 4, np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    rgb = pixels.reshape(150, 300, 4)[..., :3]
    saturated = (rgb.max(axis=-1) - rgb.min(axis=-1)) > 0.5
    assert saturated.sum() > 100  # coloured rays were drawn
    lens_scene.camera.data.prism.lens_model = "PINHOLE"
    with pytest.raises(RuntimeError, match="Real lens"):
        bpy.ops.prism.export_lens_diagram(filepath=str(tmp_path / "none.png"))


@pytest.mark.parametrize("wavelengths, channel", [("450", 2), ("650", 0)])
def test_viewport_drawing_places_the_fan_in_front_of_the_camera(lens_scene, overlay, gpu_ready, wavelengths, channel):
    """The POST_VIEW path (``draw_at_camera``) seen from the camera's side in an offscreen."""
    import gpu
    from mathutils import Matrix, Vector

    settings = lens_scene.prism.lens_overlay
    settings.wavelength_source, settings.custom_wavelengths_nm = "CUSTOM", wavelengths
    camera = lens_scene.camera
    camera.location, camera.rotation_euler = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)  # looking down -Z
    camera.data.display_size = 1.0
    bpy.context.view_layer.update()
    diagram, message = overlay.scene_diagram(lens_scene)
    assert diagram is not None, message
    size = 400
    view = Matrix(((0, 0, -1, 0), (0, 1, 0, 0), (1, 0, 0, -5), (0, 0, 0, 1)))  # from +X, up +Y
    projection = Matrix(((1 / 0.7, 0, 0, -0.5 / 0.7), (0, 1 / 0.7, 0, 0), (0, 0, -0.1, 0), (0, 0, 0, 1)))
    offscreen = gpu.types.GPUOffScreen(size, size)
    try:
        with offscreen.bind():
            framebuffer = gpu.state.active_framebuffer_get()
            framebuffer.clear(color=(0.0, 0.0, 0.0, 1.0))
            with gpu.matrix.push_pop(), gpu.matrix.push_pop_projection():
                gpu.matrix.load_projection_matrix(projection)
                gpu.matrix.load_matrix(view)
                assert overlay.draw_at_camera(lens_scene, (size, size), 1.0)
            buffer = framebuffer.read_color(0, 0, size, size, 4, 0, "FLOAT")
    finally:
        offscreen.free()
    buffer.dimensions = size * size * 4
    pixels = np.array(buffer, dtype=np.float32).reshape(size, size, 4)
    to_clip = projection @ view @ camera.matrix_world @ overlay.lens_to_camera_matrix(diagram, 1.0)
    fan = diagram.fans[0]
    hits = 0
    for ray in np.flatnonzero(fan.reached):
        a, b = fan.points_mm[ray, 0], fan.points_mm[ray, 1]  # incoming segment
        if abs(a[1]) < 0.5:
            continue
        clip = to_clip @ Vector((*(0.5 * (a + b)),))
        col, row = int(round((clip.x + 1) * size / 2)), int(round((clip.y + 1) * size / 2))
        patch = pixels[row - 1 : row + 2, col - 1 : col + 2, :3].reshape(-1, 3)
        rgb = patch[np.argmax(patch.sum(axis=1))]
        assert rgb[channel] > 0.5 and rgb[channel] > 2.0 * max(np.delete(rgb, channel)), (ray, rgb)
        hits += 1
    assert hits >= 2
    # seen from +X, the camera's -Z runs to the right: the sensor line sits at the camera
    # (x_eye = 0, column 57) and nothing is drawn behind it
    sensor_col = int(round((1 - 0.5 / 0.7) * size / 2))
    assert pixels[:, sensor_col - 1 : sensor_col + 2, :3].max() > 0.5
    assert pixels[:, : sensor_col - 12, :3].max() < 0.05


class _RecordingLayout:
    """Stands in for ``UILayout``: checks every property and operator the panels name."""

    def __init__(self, record):
        self.record = record
        self.use_property_split = self.use_property_decorate = False

    def column(self, **_kwargs):
        return self

    box = row = column

    def prop(self, data, name, **_kwargs):
        assert name in data.bl_rna.properties, f"{data} has no property {name}"
        self.record.append(name)

    def operator(self, idname, **_kwargs):
        category, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, category), name), idname
        self.record.append(idname)

    def label(self, text="", **_kwargs):
        self.record.append(text)


def test_panels_show_the_settings_and_the_status(prism_addon, lens_scene):
    panel = importlib.import_module(f"{prism_addon.__name__}.ui.lens_overlay_panel")
    record = []
    lens_scene.prism.lens_overlay.enabled = True
    panel.draw_overlay_settings(_RecordingLayout(record), bpy.context)
    for name in ("prism.toggle_lens_overlay", "wavelength_source", "rays_per_fan", "field_angle_deg",
                 "source_distance_m", "show_spot_diagram", "lens_model", "lens_file", "focus_distance",
                 "aperture_fstop", "prism.export_lens_diagram"):
        assert name in record
    assert any("RMS spot" in str(entry) for entry in record)
    assert bpy.types.VIEW3D_PT_prism_lens_overlay.bl_category == "Prism"
    camera_panel = bpy.types.PRISM_PT_camera_lens_overlay
    assert camera_panel.bl_context == "data" and camera_panel.bl_parent_id == "PRISM_PT_camera_lens"


def test_export_without_a_gpu_fails_with_the_fix(prism_addon, lens_scene, monkeypatch, tmp_path):
    export = importlib.import_module(f"{prism_addon.__name__}.ui.lens_overlay_export")
    monkeypatch.setattr(export, "_gpu_available", lambda: False)
    scenes_before = len(bpy.data.scenes)
    with pytest.raises(export.LensDiagramExportError, match="Mesa EGL"):
        export.write_lens_diagram_png(lens_scene, tmp_path / "x.png", 200, 100)
    assert len(bpy.data.scenes) == scenes_before  # the temporary GPU-initialising scene is gone
    assert not (tmp_path / "x.png").exists()


def test_focus_follows_the_focus_object_as_the_render_does(prism_addon, lens_scene, overlay):
    target = bpy.data.objects.new("Target", None)
    lens_scene.collection.objects.link(target)
    target.location = (0.3, 0.0, -2.0)  # camera at the origin looking down -Z: 2 m along the axis
    lens_scene.camera.data.dof.focus_object = target
    bpy.context.view_layer.update()
    inputs, message = overlay.overlay_inputs(lens_scene)
    assert inputs is not None, message
    assert inputs[3] == pytest.approx(2000.0)
    target.location = (0.0, 0.0, 1.0)  # behind the camera
    bpy.context.view_layer.update()
    inputs, message = overlay.overlay_inputs(lens_scene)
    assert inputs is None and "behind the camera" in message
