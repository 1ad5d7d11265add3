"""Motion blur of hair strands: their control points and radii at the shutter's time steps
(``tracer.motion.Motion.curves``), which Embree interpolates by ray time as it does moving triangles.

``export.motion`` re-exports the scene at each step; here each hair object's control points at a step are matched
to the frame's by object and order, as Cycles matches curve keys (``export_hair_curves_motion``). Per object, as
Cycles: Object ▸ Motion Blur off keeps it still at the frame; fewer Steps than the scene's are interpolated between
its own. Hair whose points carry a ``velocity`` attribute moves by it instead, each point in a straight line
(``velocity``), as Cycles takes that attribute over the steps. An object whose strands change their number of
points during the shutter (a modifier adding or removing strands) without one stays still, warned (Cycles
re-samples each changed strand's keys; Prism cannot match strands whose number changes). The matching is
``motion_steps.object_steps``, shared with point clouds and meshes.
"""

from __future__ import annotations

import numpy as np

from .motion_steps import StepRows, matched_steps, object_steps
from .velocity import moved_positions


def _point_objects(curves) -> np.ndarray:
    """int [P]: the object of each control point of ``curves`` (``CurveSegments``; every point is one of a
    segment's four)."""
    owner = np.full(len(curves.radii), -1, np.int64)
    for k in range(4):
        owner[np.asarray(curves.segments, np.int64) + k] = np.asarray(curves.object, np.int64)
    return owner


def _table(curves) -> np.ndarray:
    return np.column_stack([np.asarray(curves.points, np.float64), np.asarray(curves.radii, np.float64)])


def hair_steps(tracer_scene, steps, settings, count, warnings, drift=None, transforms=None) -> np.ndarray | None:
    """float64 [S, P, 4]: the control points (world) and radii of ``tracer_scene.curves`` at the shutter's ``count``
    time steps, from ``steps`` ((``CurveSegments`` or None, object names) exported at each), matched by object name
    and order, per object as the module says, or moved by ``drift`` (``velocity.velocity_offsets`` of their
    velocity attribute, NaN where a hair has none) and their objects' ``transforms`` (``velocity.Transforms``); None
    where no strand moves. ``settings``: object name →
    (motion blur on, steps, deformation on)."""
    curves = tracer_scene.curves
    if curves is None or not len(curves):
        return None
    names = tracer_scene.object_names
    frame = _table(curves)
    moved = None
    if drift is not None:  # the radius stays the frame's, as Cycles moves hair by its velocity
        moved = np.repeat(frame[None], len(drift), axis=0)
        moved[..., :3] = moved_positions(frame[:, :3], drift, _point_objects(curves), transforms)
    rows = StepRows(frame, _point_objects(curves), matched_steps(names, steps, _table, _point_objects),
                    changing_hair_warning, _deforming_hair_warning, moved)
    return object_steps(rows, names, settings, count, warnings)


def changing_hair_warning(name: str) -> str:
    """The warning for hair whose strands change their number of points during the shutter."""
    return (f"Hair '{name}': its strands change their number of points during the shutter (a modifier adding or "
            "removing strands over time) and have no 'velocity' attribute, so Prism cannot follow them: they are "
            "rendered still where they are at the frame, without motion blur.")


def _deforming_hair_warning(name: str) -> str:
    return (f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs its hair strands' points as they "
            "move, so any deformation is blurred too (Cycles blurs only the object's transform).")
