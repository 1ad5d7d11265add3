"""Motion blur of point clouds: their points' centres and radii at the shutter's time steps
(``tracer.motion.Motion.points``), which Embree interpolates by ray time as it does moving triangles and hair.

``export.motion`` re-exports the scene at each step; here each point cloud's points at a step are matched to the
frame's by object (instances of one cloud by occurrence) and then by point order, as Cycles matches a point
cloud's points (``export_pointcloud_motion``), through ``motion_steps.object_steps``: Object ▸ Motion Blur off
keeps a cloud still at the frame; fewer Steps than the scene's are interpolated between its own. The steps carry
each point's radius too, so points that grow or shrink blur as Cycles blurs them.

A cloud whose points carry a ``velocity`` attribute (m/s, as simulations write it) moves by it instead, each
point in a straight line, ``velocity × (step time - frame time)`` (``velocity.velocity_offsets``), whether or
not its points could be matched: Cycles 4.5 takes the attribute over the steps (a cloud moving along x whose
velocity says z blurs along z there). That is also how a cloud whose number of points changes during the shutter
(a simulation emitting or removing particles) moves; without the attribute such a cloud stays still at the frame
and is named in a warning (Cycles silently drops its motion).
"""

from __future__ import annotations

import numpy as np

from .motion_steps import StepRows, matched_steps, object_steps
from .velocity import moved_positions


def _table(points) -> np.ndarray:
    return np.column_stack([np.asarray(points.centres, np.float64), np.asarray(points.radii, np.float64)])


def _owner(points) -> np.ndarray:
    return np.asarray(points.object, np.int64)


def point_steps(tracer_scene, steps, settings, count, warnings, drift=None, transforms=None) -> np.ndarray | None:
    """float64 [S, N, 4]: the centres (world) and radii of ``tracer_scene.points`` at the shutter's ``count`` time
    steps, from ``steps`` ((``SpherePoints`` or None, object names) exported at each), per object as the module
    says, clouds with a velocity attribute moved by ``drift`` (``velocity.velocity_offsets``, NaN where a point has
    none) and their objects' ``transforms`` (``velocity.Transforms``); None where no point moves. ``settings``:
    object name → (motion blur on, steps, deformation on)."""
    points = tracer_scene.points
    if points is None or not len(points):
        return None
    names = tracer_scene.object_names
    frame = _table(points)
    moved = None
    if drift is not None:
        moved = np.repeat(frame[None], len(drift), axis=0)
        moved[..., :3] = moved_positions(frame[:, :3], drift, _owner(points), transforms)
    rows = StepRows(frame, _owner(points), matched_steps(names, steps, _table, _owner), changing_points_warning,
                    _deforming_points_warning, moved)
    return object_steps(rows, names, settings, count, warnings)


def changing_points_warning(name: str) -> str:
    """The warning for a point cloud whose number of points changes during the shutter and that has no velocity."""
    return (f"Point cloud '{name}': its number of points changes during the shutter and its points have no "
            "'velocity' attribute, so Prism cannot follow them: they are rendered still where they are at the frame, "
            "without motion blur (as Cycles renders them).")


def _deforming_points_warning(name: str) -> str:
    return (f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs its points as they move, so any "
            "deformation is blurred too (Cycles blurs only the object's transform).")
