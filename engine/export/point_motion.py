"""Motion blur of point clouds: their points' centres and radii at the shutter's time steps
(``tracer.motion.Motion.points``), which Embree interpolates by ray time as it does moving triangles and hair.

``export.motion`` re-exports the scene at each step; here each point cloud's points at a step are matched to the
frame's by object (instances of one cloud by occurrence) and then by point order, as Cycles matches a point
cloud's points (``export_pointcloud_motion``), through ``motion_steps.object_steps``: Object ▸ Motion Blur off
keeps a cloud still at the frame; fewer Steps than the scene's are interpolated between its own. A cloud whose
number of points changes during the shutter stays still at the frame, as in Cycles, and is named in a warning.
The steps carry each point's radius too, so points that grow or shrink blur as Cycles blurs them.
"""

from __future__ import annotations

import numpy as np

from .motion_steps import StepRows, matched_steps, object_steps


def _table(points) -> np.ndarray:
    return np.column_stack([np.asarray(points.centres, np.float64), np.asarray(points.radii, np.float64)])


def _owner(points) -> np.ndarray:
    return np.asarray(points.object, np.int64)


def point_steps(tracer_scene, steps, settings, count, warnings) -> np.ndarray | None:
    """float64 [S, N, 4]: the centres (world) and radii of ``tracer_scene.points`` at the shutter's ``count`` time
    steps, from ``steps`` ((``SpherePoints`` or None, object names) exported at each), per object as the module
    says; None where no point moves. ``settings``: object name → (motion blur on, steps, deformation on)."""
    points = tracer_scene.points
    if points is None or not len(points):
        return None
    names = tracer_scene.object_names
    rows = StepRows(_table(points), _owner(points), matched_steps(names, steps, _table, _owner),
                    changing_points_warning, _deforming_points_warning)
    return object_steps(rows, names, settings, count, warnings)


def changing_points_warning(name: str) -> str:
    """The warning for a point cloud whose number of points changes during the shutter."""
    return (f"Point cloud '{name}': its number of points changes during the shutter, so Prism cannot follow its "
            "points (nor can Cycles): they are rendered still where they are at the frame, without motion blur.")


def _deforming_points_warning(name: str) -> str:
    return (f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs its points as they move, so any "
            "deformation is blurred too (Cycles blurs only the object's transform).")
