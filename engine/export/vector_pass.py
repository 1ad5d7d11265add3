"""View Layer ▸ Passes ▸ Data ▸ Vector → ``DataPassInputs.triangle_motion`` and ``world_to_raster``.

Cycles' Vector pass (its "motion pass") holds how far the surface seen in a pixel moves on screen between
the previous frame and this one and between this one and the next: the scene is evaluated at frame - 1
and frame + 1 (Cycles' motion times -1 and +1, not the shutter), every object's transform and deformation
counted whatever its Object ▸ Motion Blur switch (Cycles reads that switch only for motion blur), and the
camera's motion included. Vertices are matched per object (``mesh_motion``); a mesh with a ``velocity`` attribute
moves by it, one frame's worth each way, as Cycles' pass does. With Render ▸ Motion Blur on, Cycles writes
zeros (the pass is greyed out in its panel); Prism does the same by leaving the tables out.
"""

from __future__ import annotations

import numpy as np

from .camera import render_resolution
from .mesh_motion import MeshWarnings, mesh_steps
from .motion import motion_blur_on

#: The frames the pass compares the current one with (Cycles' motion times).
_FRAME_OFFSETS = (-1.0, 1.0)


def vector_pass_wanted(scene, view_layer) -> bool:
    """The rendered view layer asks for the Vector pass and Render ▸ Motion Blur is off."""
    return bool(getattr(view_layer, "use_pass_vector", False)) and not motion_blur_on(scene, view_layer)


def world_to_raster(camera_object, depsgraph, scene) -> np.ndarray:
    """float64 [4, 4]: world point → homogeneous pixel position (x right, y up, from the lower left corner of
    the full frame) through Blender's own projection of ``camera_object`` (sensor fit, shift, pixel aspect)."""
    width, height = render_resolution(scene)
    evaluated = camera_object.evaluated_get(depsgraph)
    projection = np.array(evaluated.calc_matrix_camera(depsgraph, x=width, y=height,
                                                       scale_x=scene.render.pixel_aspect_x,
                                                       scale_y=scene.render.pixel_aspect_y), np.float64)
    view = np.linalg.inv(np.array(evaluated.matrix_world, np.float64))
    ndc_to_raster = np.array([[0.5 * width, 0.0, 0.0, 0.5 * width], [0.0, 0.5 * height, 0.0, 0.5 * height],
                              [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    # Only rows x, y and w are read: z of the projection is kept as it is.
    return ndc_to_raster @ projection @ view


def export_vector_pass(scene, depsgraph, tracer_scene, frame_set, export_meshes, warnings, frame_geometry) -> None:
    """Fill ``tracer_scene.data_passes`` for the Vector pass when it is wanted. ``frame_set(frame,
    subframe)`` re-evaluates ``depsgraph``; ``export_meshes(depsgraph)`` exports its meshes (vertices in the
    same order and frame of reference as ``tracer_scene``'s, which was exported as ``frame_geometry``)."""
    view_layer = getattr(depsgraph, "view_layer", None)
    if not vector_pass_wanted(scene, view_layer):
        return
    camera_object = scene.camera
    if camera_object.data.type == "PANO":
        warnings.append(f"View Layer '{view_layer.name}': the Vector pass of a panoramic camera "
                        f"('{camera_object.name}') is not written by Prism: the pass holds 0 (no motion).")
        return
    settings = getattr(camera_object.data, "prism", None)
    if settings is not None and settings.lens_model == "REAL_LENS":
        warnings.append(f"View Layer '{view_layer.name}': the Vector pass of camera '{camera_object.name}' is "
                        "projected through Blender's camera (a pinhole of its focal length), not through its real "
                        "lens: where the lens distorts the image, the vectors are off by that distortion.")
    frame, subframe = scene.frame_current, scene.frame_subframe
    now = world_to_raster(camera_object, depsgraph, scene)
    cameras, steps = {}, []
    try:
        for offset in _FRAME_OFFSETS:
            time = frame + subframe + offset
            whole = int(np.floor(time))
            frame_set(whole, float(time - whole))
            geometry = export_meshes(depsgraph)
            steps.append((geometry, list(geometry.object_names)))
            cameras[offset] = world_to_raster(camera_object, depsgraph, scene)
    finally:
        frame_set(frame, subframe)
    fps = float(scene.render.fps) / float(scene.render.fps_base)
    every_object = {name: (True, 1, True) for name in tracer_scene.object_names}  # Motion Blur switches: blur only
    moved, _ = mesh_steps(frame_geometry, steps, every_object, len(_FRAME_OFFSETS), warnings,
                          np.asarray(_FRAME_OFFSETS) / fps, MeshWarnings(_changing_warning, _changing_warning),
                          with_normals=False)
    frame_vertices = np.asarray(tracer_scene.vertices, np.float64)
    shifts = np.zeros((len(_FRAME_OFFSETS), *frame_vertices.shape)) if moved is None else moved - frame_vertices
    corners = tracer_scene.triangles
    motion = np.stack([shifts[k][corners] for k in range(len(_FRAME_OFFSETS))], axis=1)  # [T, 2, 3, 3]
    passes = tracer_scene.data_passes
    passes.triangle_motion = motion.astype(np.float32)
    passes.world_to_raster = np.stack([cameras[-1.0], now, cameras[1.0]])


def _changing_warning(name: str) -> str:
    return (f"Object '{name}': Vector pass: its number of vertices changes between frames (geometry added or removed "
            "over time) and it has no 'velocity' attribute, so Prism cannot follow its vertices: the pass holds the "
            "camera's motion only where it is seen, as if it stood still.")
