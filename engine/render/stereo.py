"""Output ▸ Stereoscopy (multi-view): one image per view, each seen from where Blender places that view's
camera.

Blender decides the views (Stereo 3D: left and right; Multi-View: every view in use) and, for each, the
camera's matrix and horizontal shift: ``RenderEngine.camera_model_matrix`` moves the camera by half the
Interocular Distance along its local X (and turns it in for Toe-in convergence) and
``RenderEngine.camera_shift_x`` adds the Off-Axis convergence's film shift, after the active view is set
with ``active_view_set``. Cycles asks the same three calls per view; Prism renders each view as a separate
frame of the same scene (the geometry, materials and lights are exported once).

Panoramic cameras are rendered per view from the offset camera as a whole; Cycles' spherical stereo
(an eye offset that turns with each direction) is not modelled, and a warning says so.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..export.camera import larger_side_factor, rigid_matrix
from ..tracer.scene import Camera


@dataclass(frozen=True)
class RenderView:
    """One view of a render: its name in the Render Result ('' for a plain, single-view render) and the
    tracer camera it is seen from."""

    name: str
    camera: Camera


def view_names(engine, layer: str) -> list[str]:
    """The views Blender's Render Result holds for this render, in its order (one '' without Stereoscopy)."""
    result = engine.begin_result(0, 0, 1, 1, layer=layer)
    try:
        return [view.name for view in result.views]
    finally:
        engine.end_result(result, cancel=True)


def _camera_for_view(engine, scene, camera_object, camera: Camera) -> Camera:
    """``camera`` (the scene camera as exported) moved to where the active view sees from."""
    matrix = rigid_matrix(engine.camera_model_matrix(camera_object, use_spherical_stereo=False))
    width, height = camera.resolution
    shape = (width * float(scene.render.pixel_aspect_x), height * float(scene.render.pixel_aspect_y))
    shift_x = camera.shift_x
    if camera.projection in ("perspective", "orthographic"):
        shift_x = float(engine.camera_shift_x(camera_object, use_spherical_stereo=False)) * larger_side_factor(
            camera_object.data, *shape)
    motion = camera.motion_to_world
    if motion is not None:  # the view's offset is fixed in the camera's frame: it moves with the camera
        offset = np.linalg.inv(camera.camera_to_world) @ matrix
        motion = motion @ offset
    return replace(camera, camera_to_world=matrix, shift_x=shift_x, motion_to_world=motion)


def render_views(engine, depsgraph, camera: Camera, warnings: list[str]) -> list[RenderView]:
    """Each view to render with its camera: ``[RenderView('', camera)]`` for a plain render."""
    scene = depsgraph.scene
    names = view_names(engine, depsgraph.view_layer.name) if scene.render.use_multiview else [""]
    if len(names) < 2:
        return [RenderView(names[0] if names else "", camera)]
    camera_object = scene.camera.evaluated_get(depsgraph)
    if camera.projection not in ("perspective", "orthographic"):
        warnings.append(f"Camera '{camera.name}': Stereoscopy with a panoramic camera renders each view from the "
                        "camera moved by half the Interocular Distance as a whole; Cycles' spherical stereo (an eye "
                        "offset that turns with each direction) is not modelled.")
    views = []
    for name in names:
        engine.active_view_set(name)
        views.append(RenderView(name, _camera_for_view(engine, scene, camera_object, camera)))
    return views
