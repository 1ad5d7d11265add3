"""Render ▸ Motion Blur → the tracer's motion (``tracer.motion``): the shutter, and the scene's geometry and
camera at evenly spaced times in it, as Cycles samples them.

The shutter is open for Shutter (``motion_blur_shutter``, frames) around the frame: starting at it
(Position Start), centred on it (Center) or ending at it (End). Its curve (Shutter Curve) weights the
ray time. The scene is evaluated at S = 2^(steps-1)·2 + 1 times across the shutter (Object ▸ Motion Blur
▸ Steps, the largest of the moving objects'; default 3: open, middle, close) through ``frame_set`` (the
render engine's, so the user's frame is untouched; restored after) and re-exported: moving and deforming
meshes alike get their vertices at each time, hair its strands' points (``hair_motion``), point clouds their
points (``point_motion``). An object whose
Motion Blur is off stays where it is at the frame, as in Cycles; an object with fewer steps than S is
interpolated between its own steps.
"""

from __future__ import annotations

import numpy as np

from ..tracer.motion import Motion, motion_step_count, shutter_times
from .camera import rigid_matrix
from .hair_motion import hair_steps
from .motion_steps import is_still, resample
from .point_motion import point_steps, velocity_steps
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


def export_motion(scene, depsgraph, tracer_scene, frame_set, export_meshes, warnings, point_velocity=None) -> None:
    """Give ``tracer_scene`` (already exported at the frame) its motion blur: ``camera.shutter_times``,
    ``camera.motion_to_world`` and ``motion`` where something moves. ``frame_set(frame, subframe)``
    re-evaluates ``depsgraph``; ``export_meshes(depsgraph)`` exports its meshes as at the frame;
    ``point_velocity`` (``ExportedGeometry.point_velocity``) the points' velocity attribute at the frame."""
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
    vertices, normals, cameras, changed, clouds, strands = [], [], [], False, [], []
    try:
        for time in frames:
            whole = int(np.floor(time))
            frame_set(whole, float(time - whole))
            geometry = export_meshes(depsgraph)
            if geometry.vertices.shape != tracer_scene.vertices.shape or not np.array_equal(
                    geometry.triangles, tracer_scene.triangles):
                changed = True
            else:
                vertices.append(geometry.vertices)
                normals.append(geometry.corner_normals)
            step_names = list(getattr(geometry, "object_names", []))
            clouds.append((getattr(geometry, "points", None), step_names))
            strands.append((getattr(geometry, "curves", None), step_names))
            cameras.append(rigid_matrix(camera_object.evaluated_get(depsgraph).matrix_world))
    finally:
        frame_set(frame, subframe)
    camera.shutter_times = shutter_curve_times(scene)
    cameras = np.asarray(cameras)
    if not np.allclose(cameras, cameras[:1], rtol=0.0, atol=1e-12):
        camera.motion_to_world = cameras
    hair = hair_steps(tracer_scene, strands, settings, count, warnings)
    fps = float(scene.render.fps) / float(scene.render.fps_base)
    seconds = (frames - (frame + subframe)) / fps  # each step's time from the frame's
    points = point_steps(tracer_scene, clouds, settings, count, warnings, velocity_steps(point_velocity, seconds))
    steps, corner = None, None
    if changed:
        warnings.append(f"Scene '{scene.name}': Motion Blur: a mesh changes its vertices or faces during the shutter "
                        "(a modifier that adds or removes geometry over time), so Prism cannot follow its vertices: "
                        "meshes are rendered still where they are at the frame; the camera's motion is blurred.")
    elif not is_still(np.stack(vertices)):
        steps = np.stack(vertices)
        corner = np.stack(normals) if tracer_scene.corner_normals is not None and len(normals[0]) else None
        _per_object(tracer_scene, settings, steps, corner, count, warnings)
        if is_still(steps):  # nothing moves after Object settings
            steps, corner = None, None
    if steps is not None or hair is not None or points is not None:  # else still: no time steps in Embree
        tracer_scene.motion = Motion(steps, corner, hair, points)


def _per_object(tracer_scene, settings, steps, corner, count, warnings) -> None:
    """Object ▸ Motion Blur per object, in place: off → still at the frame; fewer steps → resampled."""
    if tracer_scene.triangle_object is None:
        return
    piece_vertex = np.full(len(tracer_scene.vertices), -1, np.int64)
    piece_vertex[tracer_scene.triangles.reshape(-1)] = np.repeat(tracer_scene.triangle_object, 3)
    for index, name in enumerate(tracer_scene.object_names):
        blur, own_steps, deform = settings.get(name, (True, 1, True))
        on_vertex = piece_vertex == index
        on_triangle = tracer_scene.triangle_object == index
        if not on_vertex.any() or np.array_equal(steps[:, on_vertex], np.broadcast_to(
                steps[:1, on_vertex], steps[:, on_vertex].shape)):
            continue  # does not move
        if not blur:
            steps[:, on_vertex] = tracer_scene.vertices[on_vertex]
            if corner is not None:
                corner[:, on_triangle] = tracer_scene.corner_normals[on_triangle]
            continue
        emits = [tracer_scene.materials[m].name for m in np.unique(tracer_scene.triangle_material[on_triangle])
                 if tracer_scene.materials[m].emission_strength > 0.0]
        if emits:
            warnings.append(f"Object '{name}' emits light ({', '.join(emits)}) and moves during the shutter: it is seen "
                            "blurred, but the light it casts is sampled where it stands at the frame (Cycles: "
                            "where it is at each ray's time), so its lighting of other surfaces is not blurred "
                            "exactly.")
        own = min(motion_step_count(own_steps), count)
        if own < count:
            steps[:, on_vertex] = resample(steps[:, on_vertex], own)
            if corner is not None:
                corner[:, on_triangle] = resample(corner[:, on_triangle], own)
        if not deform:
            warnings.append(f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs the mesh's vertices as "
                            "they move, so any deformation (armature, shape keys, modifiers) is blurred too (Cycles "
                            "blurs only the object's transform).")


def motion_setting_warnings(scene, light_tracing: str, view_layer=None) -> list[str]:
    """Warnings for the motion blur settings Prism does not follow (rolling shutter; light tracing forced on)."""
    if not motion_blur_on(scene, view_layer):
        return []
    found = []
    cycles = getattr(scene, "cycles", None)
    if cycles is not None and getattr(cycles, "rolling_shutter_type", "NONE") != "NONE":
        found.append(f"Scene '{scene.name}': Motion Blur ▸ Rolling Shutter is on, but Prism has no rolling shutter: "
                     "every row of the image is exposed over the same shutter time (a global shutter).")
    if light_tracing == "ON":
        found.append(f"Scene '{scene.name}': Light Paths ▸ Caustics ▸ Light Tracing is On, but light paths have no ray "
                     "time yet: with Motion Blur on, caustics are path traced (light tracing off).")
    return found
