"""The lens overlay in the 3D viewport: ray fans through the active camera's real lens.

Two ``SpaceView3D`` draw handlers, added lazily when the overlay is switched on (never at
register time, never in background mode) and removed when it is switched off or the
add-on unregisters:

- ``POST_VIEW``: the lens cross-section, rays, stop and sensor, in world space at the
  active camera. Lens coordinates map to the camera's local space with the sensor at the
  camera origin, the lens axis along the camera's -Z and the meridional plane its local
  Y-Z plane, scaled so the front vertex sits ``LENGTH_IN_DISPLAY_SIZES`` x the camera's
  Display Size in front of the origin (the camera gizmo's own size), whatever the lens's
  millimetres.
- ``POST_PIXEL``: the spot diagram inset (bottom right, drawn by
  ``lens_spot_inset.draw_spot_inset``) with RMS radii, and the reason
  when nothing can be drawn.

Line widths follow Preferences > Interface > Line Width through
``preferences.system.ui_line_width`` (already DPI-scaled): rays 1.5x, outlines 1x.
The optics come ready from ``engine.tracer.lens.fan`` (computed once per change of the
lens, focus, f-stop or overlay settings and cached); this module only draws polylines.
"""

from __future__ import annotations

import os
import traceback

import bpy

from ..engine.tracer.errors import PrismInputError
from .lens_overlay_colours import AXIS_RGBA, BLOCKED_ALPHA, OUTLINE_RGBA, SENSOR_RGBA, STOP_RGBA, display_colours
from .lens_spot_inset import draw_spot_inset

LENGTH_IN_DISPLAY_SIZES = 1.0

_handles: dict = {}
_batch_cache: dict = {"key": None, "batches": None}


# ---- what to draw: the scene's settings -> a cached LensDiagram ------------------------
_diagram_cache: dict = {"key": None, "diagram": None, "message": ""}


def overlay_settings(scene):
    """``Scene.prism.lens_overlay`` or None (settings not registered)."""
    return getattr(getattr(scene, "prism", None), "lens_overlay", None)


def sensor_half_height_mm(scene, camera_data):
    """Half the film height (mm) the render uses (the meridional plane is the camera's Y)."""
    from ..engine.export.camera import film_size_mm, render_resolution

    return 0.5 * film_size_mm(camera_data, *render_resolution(scene))[1]


def overlay_inputs(scene):
    """``(inputs, message)``: a hashable tuple of everything the diagram depends on, or None
    and the reason (in words a user can act on) when there is nothing to draw."""
    settings = overlay_settings(scene)
    camera = scene.camera
    if settings is None:
        return None, "Lens overlay: Prism's settings are not registered."
    if camera is None or camera.type != "CAMERA":
        return None, "Lens overlay: the scene has no active camera; add one (or set Scene > Camera)."
    prism = getattr(camera.data, "prism", None)
    if getattr(prism, "lens_model", "") != "REAL_LENS":
        return None, f"Lens overlay: camera '{camera.name}' has no real lens; set Prism > Lens Model to Real lens."
    path = prism.lens_path() if hasattr(prism, "lens_path") else None
    if not path or not os.path.isfile(path):
        return None, f"Lens overlay: camera '{camera.name}': lens file '{path or ''}' not found; choose a lens."
    from ..engine.export.camera import focus_distance_m

    try:  # exactly as the render exports it (focus object, bone, behind-the-camera check)
        focus_m = float(focus_distance_m(camera))
    except PrismInputError as error:
        return None, f"Lens overlay: {error}"
    if not focus_m > 0.0:  # as the render's real-lens camera
        return None, f"Lens overlay: camera '{camera.name}': focus distance must be positive."
    try:
        wavelengths = tuple(settings.wavelengths_nm(scene.prism))
    except PrismInputError as error:  # the custom list
        return None, str(error)
    inputs = (
        path,
        os.stat(path).st_mtime_ns,
        round(float(camera.data.dof.aperture_fstop), 6),
        round(1000.0 * focus_m, 6),
        wavelengths,
        int(settings.rays_per_fan),
        round(float(settings.field_angle_deg), 6),
        round(1000.0 * float(settings.source_distance_m), 6),
        round(sensor_half_height_mm(scene, camera.data), 6),
    )
    return inputs, ""


def compute_diagram(inputs):
    """The ``LensDiagram`` for ``overlay_inputs`` (may raise ``PrismInputError``): the lens
    stopped and focused exactly as the render's ``RealLensCamera`` does it."""
    from ..engine.tracer.lens.fan import lens_diagram
    from ..engine.tracer.lens.lens_file import load_lens

    path, _, fstop, focus_mm, wavelengths, rays, field, source_mm, half_height = inputs
    system = load_lens(path).with_fstop(fstop)
    return lens_diagram(
        system, wavelengths, n_rays=rays, field_angle_deg=field, source_distance_mm=source_mm,
        focus_distance_mm=focus_mm, sensor_half_height_mm=half_height,
    )


def scene_diagram(scene):
    """``(diagram, message)`` for ``scene``'s camera, recomputed only when an input changed;
    ``diagram`` is None when nothing can be drawn and ``message`` says why."""
    inputs, message = overlay_inputs(scene)
    if inputs is None:
        return None, message
    if _diagram_cache["key"] != inputs:
        diagram, message = None, ""
        try:
            diagram = compute_diagram(inputs)
        except Exception as error:  # noqa: BLE001 - a draw callback must never raise
            message = str(error) if isinstance(error, PrismInputError) else f"Lens overlay failed: {error!r}"
            if not isinstance(error, PrismInputError):
                traceback.print_exc()
        _diagram_cache.update(key=inputs, diagram=diagram, message=message)
    return _diagram_cache["diagram"], _diagram_cache["message"]


# ---- primitives shared with the PNG export ---------------------------------------------
def _segments_and_colours(diagram, show_outlines=True, show_sensor=True):
    """Line segments in lens coordinates (x, y, z mm) with RGBA per vertex, as numpy arrays:
    ``(rays_pos, rays_col, frame_pos, frame_col)``; the frame is outlines, stop, sensor, axis."""
    import numpy as np

    ray_pos, ray_col = [], []
    for fan, rgb in zip(diagram.fans, display_colours(diagram.wavelengths_nm)):
        starts, ends, ray = fan.segments()
        alpha = np.where(fan.reached[ray], 1.0, BLOCKED_ALPHA)
        colour = np.column_stack([np.tile(rgb, (len(ray), 1)), alpha])
        ray_pos.append(np.stack([starts, ends], axis=1).reshape(-1, 3))
        ray_col.append(np.repeat(colour, 2, axis=0))
    frame_pos, frame_col = [], []

    def polyline(points_zy, rgba):
        zy = np.asarray(points_zy, dtype=np.float64)
        xyz = np.column_stack([np.zeros(len(zy)), zy[:, 1], zy[:, 0]])
        frame_pos.append(np.stack([xyz[:-1], xyz[1:]], axis=1).reshape(-1, 3))
        frame_col.append(np.tile(rgba, (2 * (len(zy) - 1), 1)))

    z_min, z_max, _ = diagram.bounds_mm
    polyline([(z_min, 0.0), (z_max, 0.0)], AXIS_RGBA)
    if show_outlines:
        for outline in diagram.outlines.elements:
            polyline(outline, OUTLINE_RGBA)
        for bar in diagram.outlines.stop:
            polyline(bar, STOP_RGBA)
    if show_sensor:
        h = diagram.sensor_half_height_mm
        polyline([(diagram.sensor_z_mm, -h), (diagram.sensor_z_mm, h)], SENSOR_RGBA)

    def stack(parts, width):
        return np.concatenate(parts).astype(np.float32) if parts else np.zeros((0, width), np.float32)

    return stack(ray_pos, 3), stack(ray_col, 4), stack(frame_pos, 3), stack(frame_col, 4)


def build_batches(diagram, show_outlines=True, show_sensor=True):
    """GPU batches ``(shader, frame_batch, rays_batch)`` of the cross-section in lens coordinates."""
    import gpu
    from gpu_extras.batch import batch_for_shader

    shader = gpu.shader.from_builtin("POLYLINE_SMOOTH_COLOR")
    rays_pos, rays_col, frame_pos, frame_col = _segments_and_colours(diagram, show_outlines, show_sensor)
    frame = batch_for_shader(shader, "LINES", {"pos": frame_pos, "color": frame_col})
    rays = batch_for_shader(shader, "LINES", {"pos": rays_pos, "color": rays_col})
    return shader, frame, rays


def draw_batches(batches, viewport_size, line_width):
    """Draw ``build_batches`` output with the current matrices, no depth test. Rays blend
    additively, so where the fans of several wavelengths overlap they add up towards white
    and where they separate (dispersion) their own colours show, as light would."""
    import gpu

    shader, frame, rays = batches
    gpu.state.blend_set("ALPHA")
    gpu.state.depth_test_set("NONE")
    shader.bind()
    shader.uniform_float("viewportSize", viewport_size)
    shader.uniform_float("lineWidth", line_width)
    frame.draw(shader)
    gpu.state.blend_set("ADDITIVE")
    shader.uniform_float("lineWidth", 1.5 * line_width)
    rays.draw(shader)
    gpu.state.blend_set("NONE")


# ---- the viewport handlers ---------------------------------------------------------------
def lens_to_camera_matrix(diagram, display_size):
    """4x4 matrix from lens coordinates (mm) to the camera's local space (see module docstring)."""
    from mathutils import Matrix

    z_sensor = diagram.sensor_z_mm  # the front vertex is at z = 0
    s = LENGTH_IN_DISPLAY_SIZES * display_size / max(z_sensor, 1e-6)
    return Matrix(((s, 0, 0, 0), (0, s, 0, 0), (0, 0, s, -z_sensor * s), (0, 0, 0, 1)))


def _line_width(context):
    return max(1.0, float(getattr(context.preferences.system, "ui_line_width", 1.0)))


def draw_at_camera(scene, viewport_size, line_width):
    """Draw ``scene``'s lens diagram at its active camera, in world space, with the current
    view and projection matrices. Returns whether there was something to draw."""
    import gpu

    settings = overlay_settings(scene)
    diagram, _ = scene_diagram(scene)
    if diagram is None:
        return False
    key = (id(diagram), settings.show_outlines, settings.show_sensor)
    if _batch_cache["key"] != key:
        _batch_cache["batches"] = build_batches(diagram, settings.show_outlines, settings.show_sensor)
        _batch_cache["key"] = key
    camera = scene.camera
    with gpu.matrix.push_pop():
        gpu.matrix.multiply_matrix(camera.matrix_world @ lens_to_camera_matrix(diagram, camera.data.display_size))
        draw_batches(_batch_cache["batches"], viewport_size, line_width)
    return True


def _overlay_shown(context):
    settings = overlay_settings(context.scene)
    overlay = getattr(context.space_data, "overlay", None)
    return settings is not None and settings.enabled and getattr(overlay, "show_overlays", True)


def _draw_view():
    context = bpy.context
    if _overlay_shown(context):
        draw_at_camera(context.scene, (context.region.width, context.region.height), _line_width(context))


def _sidebar_width(context):
    if not context.preferences.system.use_region_overlap:
        return 0
    return next((r.width for r in context.area.regions if r.type == "UI" and r.width > 1), 0)


def _draw_pixel():
    import blf

    context = bpy.context
    if not _overlay_shown(context):
        return
    settings = overlay_settings(context.scene)
    diagram, message = scene_diagram(context.scene)
    scale = context.preferences.system.ui_scale or 1.0
    margin = 20 * scale
    if diagram is None:
        blf.size(0, 12 * scale)
        blf.color(0, 1.0, 0.55, 0.4, 1.0)
        blf.position(0, margin, margin, 0)
        blf.draw(0, message)
        return
    if settings.show_spot_diagram:
        size = 160 * scale
        right = context.region.width - _sidebar_width(context) - margin
        draw_spot_inset(diagram, right - size, margin, size, 11 * scale)


def handlers_active() -> bool:
    """Whether the viewport draw handlers are installed."""
    return bool(_handles)


def _in_background() -> bool:
    return bpy.app.background


def add_handlers() -> bool:
    """Install the draw handlers (once). Does nothing in background mode; returns whether
    they are installed."""
    if _in_background():
        return False
    if not _handles:
        _handles["view"] = bpy.types.SpaceView3D.draw_handler_add(_draw_view, (), "WINDOW", "POST_VIEW")
        _handles["pixel"] = bpy.types.SpaceView3D.draw_handler_add(_draw_pixel, (), "WINDOW", "POST_PIXEL")
    return True


def remove_handlers():
    """Remove the draw handlers, if installed, and drop the cached batches."""
    for handle in _handles.values():
        bpy.types.SpaceView3D.draw_handler_remove(handle, "WINDOW")
    _handles.clear()
    _batch_cache.update(key=None, batches=None)


def sync_handlers():
    """Handlers installed exactly when some scene has the overlay enabled (never headless)."""
    wanted = any(getattr(overlay_settings(s), "enabled", False) for s in bpy.data.scenes)
    if wanted:
        add_handlers()
    else:
        remove_handlers()
    tag_redraw()


def tag_redraw():
    """Redraw every 3D viewport."""
    window_manager = bpy.context.window_manager
    for window in getattr(window_manager, "windows", ()):
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


@bpy.app.handlers.persistent
def _on_load_post(*_args):
    sync_handlers()


def register():
    bpy.app.handlers.load_post.append(_on_load_post)


def unregister():
    if _on_load_post in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(_on_load_post)
    remove_handlers()
