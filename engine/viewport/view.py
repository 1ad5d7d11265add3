"""What a 3D viewport shows → the tracer camera and border that render it.

The region's window matrix is the whole projection, zoom and pan of the view included, so one
formula serves the free view and the camera view alike: a perspective window matrix ``P`` puts the
point (x, y, -1) of view space at NDC (P00 x - P02, P11 y - P12), so the region spans
``2 / P00`` x ``2 / P11`` there, centred on (P02 / P00, P12 / P11). At a focal length ``f`` that is
a film of ``2 f / P00`` x ``2 f / P11`` mm with a shift; in camera view ``f`` is the camera's own
focal length, so a real lens sees the film in millimetres exactly where Blender draws the camera
frame (the passepartout around it is film beyond the frame), and thin-lens depth of field keeps its
aperture. An orthographic window matrix puts view-space x at NDC P00 x + P03, so the region spans
``2 / P00`` x ``2 / P11`` metres centred on (-P03 / P00, -P13 / P11). Blender draws an orthographic
free view from half its clip range behind the view's centre to half beyond, so its rays start
``clip_end / 2`` behind the centre (as Cycles places them).
The render border is the viewport's own (View ▸ Render Region) in a free view, the scene's (a fraction
of the camera frame) in camera view.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..export.camera import rigid_matrix
from ..tracer.errors import PrismInputError
from ..tracer.scene import Camera

#: Focal length of a free view's pinhole: any value gives the same rays.
FREE_VIEW_FOCAL_MM = 50.0


@dataclass(frozen=True)
class ViewportView:
    """A region's view: size in pixels, ``view_matrix`` (world → view) and ``window_matrix``
    (projection) as 16 floats row by row, whether it is a perspective and a camera view, the render
    border as fractions (min x, min y, max x, max y; y up) of the region (free view) or of the camera
    frame (camera view), None when off, in camera view the camera frame in region pixels (left,
    bottom, right, top), and the view's Clip End (m)."""

    width: int
    height: int
    view_matrix: tuple
    window_matrix: tuple
    perspective: bool
    camera_view: bool
    border: tuple | None
    frame: tuple | None = None
    clip_end_m: float = 1000.0

    @property
    def projection(self) -> np.ndarray:
        return np.asarray(self.window_matrix, dtype=np.float64).reshape(4, 4)


def _flat(matrix) -> tuple:
    return tuple(float(value) for row in matrix for value in row)


def view_of(context, scene) -> ViewportView:
    """The view of ``context``'s region (a ``SpaceView3D`` window region)."""
    region, view, space = context.region, context.region_data, context.space_data
    camera_view = view.view_perspective == "CAMERA"
    if camera_view:
        render = scene.render
        on, source, prefix = render.use_border, render, "border_"
    else:
        on, source, prefix = space.use_render_border, space, "render_border_"
    border = frame = None
    if on:
        border = tuple(float(getattr(source, prefix + name)) for name in ("min_x", "min_y", "max_x", "max_y"))
        if border == (0.0, 0.0, 1.0, 1.0):
            border = None
    if camera_view and border is not None and scene.camera is not None:
        frame = camera_frame(scene, view.perspective_matrix, region.width, region.height)
    return ViewportView(int(region.width), int(region.height), _flat(view.view_matrix), _flat(view.window_matrix),
                        bool(view.is_perspective), camera_view, border, frame, float(space.clip_end))


def camera_frame(scene, perspective_matrix, width: int, height: int) -> tuple:
    """(left, bottom, right, top) region pixels of the scene camera's frame (Blender's own
    ``view_frame``: sensor fit, shift and the render's aspect), seen through ``perspective_matrix``."""
    camera = scene.camera
    xs, ys = [], []
    for corner in camera.data.view_frame(scene=scene):
        clip = perspective_matrix @ (camera.matrix_world @ corner).to_4d()
        xs.append((clip.x / clip.w + 1.0) * 0.5 * width)
        ys.append((clip.y / clip.w + 1.0) * 0.5 * height)
    return min(xs), min(ys), max(xs), max(ys)


def view_camera(view: ViewportView, scene_camera: Camera | None) -> tuple[Camera, tuple | None]:
    """(tracer camera rendering the whole region, border in pixels (x0, y0, x1, y1; rows from the
    top) or None). ``scene_camera`` is the exported scene camera, used in camera view (its lens
    model, focal length and depth of field)."""
    if view.camera_view and scene_camera is None:
        raise PrismInputError("The viewport looks through a camera that is not the scene's camera.")
    if view.camera_view and scene_camera.projection not in ("perspective", "orthographic"):
        raise PrismInputError(
            f"The viewport looks through the panoramic camera '{scene_camera.name}': render it with F12, or "
            "leave the camera view (Numpad 0) to render the viewport."
        )
    to_world = rigid_matrix(np.linalg.inv(np.asarray(view.view_matrix, dtype=np.float64).reshape(4, 4)))
    placement = _perspective(view, scene_camera) if view.perspective else _orthographic(view)
    placement.update(camera_to_world=to_world, resolution=(view.width, view.height))
    if view.camera_view:
        camera = replace(scene_camera, **placement)
    else:
        camera = Camera(name="Viewport", **placement)
    return camera, _border_pixels(view)


def _perspective(view: ViewportView, scene_camera: Camera | None) -> dict:
    p = view.projection
    focal = scene_camera.focal_length_mm if view.camera_view else FREE_VIEW_FOCAL_MM
    film_width, film_height = 2.0 * focal / p[0, 0], 2.0 * focal / p[1, 1]
    larger = max(film_width, film_height)
    # ``scene.Camera`` gives the shift in units of the larger film side (``stages.camera``)
    return dict(projection="perspective", focal_length_mm=focal, film_width_mm=film_width,
                film_height_mm=film_height, shift_x=p[0, 2] / p[0, 0] * focal / larger,
                shift_y=p[1, 2] / p[1, 1] * focal / larger)


def _orthographic(view: ViewportView) -> dict:
    p = view.projection
    width_m, height_m = 2.0 / p[0, 0], 2.0 / p[1, 1]
    larger = max(width_m, height_m)
    placement = dict(projection="orthographic", ortho_width_m=width_m, ortho_height_m=height_m,
                     shift_x=-p[0, 3] / p[0, 0] / larger, shift_y=-p[1, 3] / p[1, 1] / larger)
    if not view.camera_view:
        placement["ortho_start_m"] = 0.5 * view.clip_end_m
    return placement


def _border_pixels(view: ViewportView) -> tuple | None:
    if view.border is None:
        return None
    min_x, min_y, max_x, max_y = view.border
    width, height = view.width, view.height
    left, bottom, right, top = view.frame if view.camera_view else (0.0, 0.0, float(width), float(height))
    x0, x1 = (int(np.clip(round(left + f * (right - left)), 0, width)) for f in (min_x, max_x))
    y0, y1 = (int(np.clip(round(bottom + f * (top - bottom)), 0, height)) for f in (min_y, max_y))
    if x1 <= x0 or y1 <= y0:
        raise PrismInputError("The render region lies outside the viewport: pan the view or clear it (Ctrl+Alt+B).")
    return x0, height - y1, x1, height - y0
