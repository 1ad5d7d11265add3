"""Render ▸ Motion Blur → the tracer's motion (``tracer.motion``): the shutter, and the scene's geometry and
camera at evenly spaced times in it, as Cycles samples them.

The shutter is open for Shutter (``motion_blur_shutter``, frames) around the frame: starting at it
(Position Start), centred on it (Center) or ending at it (End). Its curve (Shutter Curve) weights the
ray time. The scene is evaluated at S = 2^(steps-1)·2 + 1 times across the shutter (Object ▸ Motion Blur
▸ Steps, the largest of the moving objects'; default 3: open, middle, close) through ``frame_set`` (the
render engine's, so the user's frame is untouched; restored after) and re-exported: moving and deforming
meshes alike get their vertices at each time (``mesh_motion``; by their velocity attribute where they have one),
hair its strands' points (``hair_motion``), point clouds their points (``point_motion``). An object whose Motion
Blur is off stays where it is at the frame, as in Cycles; an object with fewer steps than S is interpolated
between its own steps.
"""

from __future__ import annotations

import numpy as np

from ..tracer.motion import Motion, motion_step_count, shutter_times
from .camera import rigid_matrix
from .hair_motion import hair_steps
from .mesh_motion import MeshWarnings, changing_mesh_warning, deforming_mesh_warning, mesh_steps, step_transforms
from .point_motion import point_steps
from .velocity import velocity_offsets
from .view_layer_filter import layer_filter

#: Where the shutter's middle lies relative to the frame, in shutter lengths (Cycles' motion position).
_SHUTTER_CENTRE = {"START": 0.5, "CENTER": 0.0, "END": -0.5}
_CURVE_SAMPLES = 256  # Cycles tabulates the shutter curve at 256 points (RAMP_TABLE_SIZE)


def motion_blur_on(scene, view_layer=None) -> bool:
    """Render ▸ Motion Blur on with an open shutter, and the rendered ``view_layer``'s Filter ▸ Motion Blur on
    (Cycles needs both)."""
    return (bool(scene.render.use_motion_blur) and float(scene.render.motion_blur_shutter) > 0.0
            and layer_filter(view_layer).motion_blur)


def step_frames(scene, count: int) -> np.ndarray:
    """The frames (float, subframes included) of the shutter's ``count`` evenly spaced time steps."""
    shutter = float(scene.render.motion_blur_shutter)
    frame = scene.frame_current + scene.frame_subframe
    centre = frame + _SHUTTER_CENTRE.get(scene.render.motion_blur_position, 0.0) * shutter
    return centre + shutter * (np.linspace(0.0, 1.0, count) - 0.5)


def shutter_curve_times(scene) -> np.ndarray:
    """``tracer.motion.shutter_times`` of Render ▸ Motion Blur ▸ Shutter Curve."""
    curve = scene.render.motion_blur_shutter_curve
    curve.initialize()
    values = [curve.evaluate(curve.curves[0], x) for x in np.linspace(0.0, 1.0, _CURVE_SAMPLES)]
    return shutter_times(values)


def _object_settings(name):
    """(motion blur on, steps, deformation on) of the object named ``name`` (Object ▸ Motion Blur)."""
    import bpy

    obj = bpy.data.objects.get(name)
    settings = getattr(obj, "cycles", None)
    if settings is None:
        return True, 1, True
    return bool(settings.use_motion_blur), int(settings.motion_steps), bool(settings.use_deform_motion)


def export_motion(scene, depsgraph, tracer_scene, frame_set, export_meshes, warnings, frame_geometry) -> None:
    """Give ``tracer_scene`` (already exported at the frame, from ``frame_geometry``, its
    ``meshes.ExportedGeometry``) its motion blur: ``camera.shutter_times``, ``camera.motion_to_world`` and
    ``motion`` where something moves. ``frame_set(frame, subframe)`` re-evaluates ``depsgraph``;
    ``export_meshes(depsgraph)`` exports its geometry as at the frame."""
    if not motion_blur_on(scene, getattr(depsgraph, "view_layer", None)):
        return
    camera = tracer_scene.camera
    names = sorted(set(tracer_scene.object_names))
    settings = {name: _object_settings(name) for name in names}
    camera_object = scene.camera
    camera_steps = motion_step_count(camera_object.cycles.motion_steps) if hasattr(camera_object, "cycles") else 3
    count = max([camera_steps] + [motion_step_count(s[1]) for s in settings.values() if s[0]])
    frames = step_frames(scene, count)
    frame, subframe = scene.frame_current, scene.frame_subframe
    meshes, cameras, clouds, strands = [], [], [], []
    try:
        for time in frames:
            whole = int(np.floor(time))
            frame_set(whole, float(time - whole))
            geometry = export_meshes(depsgraph)
            step_names = list(getattr(geometry, "object_names", []))
            meshes.append((geometry, step_names))
            clouds.append((getattr(geometry, "points", None), step_names))
            strands.append((getattr(geometry, "curves", None), step_names))
            cameras.append(rigid_matrix(camera_object.evaluated_get(depsgraph).matrix_world))
    finally:
        frame_set(frame, subframe)
    camera.shutter_times = shutter_curve_times(scene)
    cameras = np.asarray(cameras)
    if not np.allclose(cameras, cameras[:1], rtol=0.0, atol=1e-12):
        camera.motion_to_world = cameras
    fps = float(scene.render.fps) / float(scene.render.fps_base)
    seconds = (frames - (frame + subframe)) / fps  # each step's time from the frame's
    transforms = step_transforms(frame_geometry, meshes)  # for what moves by its velocity attribute
    hair = hair_steps(tracer_scene, strands, settings, count, warnings,
                      velocity_offsets(frame_geometry.curve_velocity, seconds), transforms)
    points = point_steps(tracer_scene, clouds, settings, count, warnings,
                         velocity_offsets(frame_geometry.point_velocity, seconds), transforms)
    steps, corner = mesh_steps(frame_geometry, meshes, settings, count, warnings, seconds,
                               MeshWarnings(changing_mesh_warning, deforming_mesh_warning))
    if steps is not None or hair is not None or points is not None:  # else still: no time steps in Embree
        tracer_scene.motion = Motion(steps, corner, hair, points)


def motion_setting_warnings(scene, view_layer=None) -> list[str]:
    """Warnings for the motion blur settings Prism does not follow (rolling shutter)."""
    if not motion_blur_on(scene, view_layer):
        return []
    cycles = getattr(scene, "cycles", None)
    if cycles is not None and getattr(cycles, "rolling_shutter_type", "NONE") != "NONE":
        return [f"Scene '{scene.name}': Motion Blur ▸ Rolling Shutter is on, but Prism has no rolling shutter: every "
                "row of the image is exposed over the same shutter time (a global shutter)."]
    return []
