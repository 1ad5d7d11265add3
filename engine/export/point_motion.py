"""Motion blur of point clouds: their points' centres and radii at the shutter's time steps
(``tracer.motion.Motion.points``), which Embree interpolates by ray time as it does moving triangles and hair.

``export.motion`` re-exports the scene at each step; here each point cloud's points at a step are matched to the
frame's by object (instances of one cloud by occurrence) and then by point order, as Cycles matches a point
cloud's points (``export_pointcloud_motion``), through ``motion_steps.object_steps``: Object ▸ Motion Blur off
keeps a cloud still at the frame; fewer Steps than the scene's are interpolated between its own. The steps carry
each point's radius too, so points that grow or shrink blur as Cycles blurs them.

A cloud whose number of points changes during the shutter (a simulation emitting or removing particles) cannot be
matched point by point: where its points carry a ``velocity`` attribute (m/s, as simulations write it), each
moves in a straight line by it, ``velocity × (step time - frame time)`` (``velocity.velocity_offsets``), as Cycles
blurs points by their velocity; without one the cloud stays still at the frame and is named in a warning (Cycles
silently drops its motion). Cycles moves the points whose index the step's cloud still has to that step's point of the
same index instead, which is another particle once one has died; Prism uses the velocity for all of them.
"""

from __future__ import annotations

import numpy as np

from .motion_steps import StepRows, matched_steps, object_steps


def _table(points) -> np.ndarray:
    return np.column_stack([np.asarray(points.centres, np.float64), np.asarray(points.radii, np.float64)])


def _owner(points) -> np.ndarray:
    return np.asarray(points.object, np.int64)


def point_steps(tracer_scene, steps, settings, count, warnings, drift=None) -> np.ndarray | None:
    """float64 [S, N, 4]: the centres (world) and radii of ``tracer_scene.points`` at the shutter's ``count`` time
    steps, from ``steps`` ((``SpherePoints`` or None, object names) exported at each), per object as the module
    says, clouds whose number of points changes moved by ``drift`` (``velocity.velocity_offsets``, NaN where a point
    has no velocity); None where no point moves. ``settings``: object name → (motion blur on, steps, deformation on)."""
    points = tracer_scene.points
    if points is None or not len(points):
        return None
    names = tracer_scene.object_names
    frame = _table(points)
    unmatched = None
    if drift is not None:
        unmatched = np.repeat(frame[None], len(drift), axis=0)
        unmatched[..., :3] += drift
    rows = StepRows(frame, _owner(points), matched_steps(names, steps, _table, _owner), changing_points_warning,
                    _deforming_points_warning, unmatched)
    return object_steps(rows, names, settings, count, warnings)


def changing_points_warning(name: str) -> str:
    """The warning for a point cloud whose number of points changes during the shutter and that has no velocity."""
    return (f"Point cloud '{name}': its number of points changes during the shutter and its points have no "
            "'velocity' attribute, so Prism cannot follow them: they are rendered still where they are at the frame, "
            "without motion blur (as Cycles renders them).")


def _deforming_points_warning(name: str) -> str:
    return (f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs its points as they move, so any "
            "deformation is blurred too (Cycles blurs only the object's transform).")
