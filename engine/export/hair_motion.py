"""Motion blur of hair strands: their control points and radii at the shutter's time steps
(``tracer.motion.Motion.curves``), which Embree interpolates by ray time as it does moving triangles.

``export.motion`` re-exports the scene at each step; here each hair object's control points at a step are matched
to the frame's by object and order, as Cycles matches curve keys (``export_hair_curves_motion``). Per object, as
Cycles: Object ▸ Motion Blur off keeps it still at the frame; fewer Steps than the scene's are interpolated between
its own. An object whose strands change their number of points during the shutter (a modifier adding or removing
strands) stays still, warned (Cycles re-samples each changed strand's keys; Prism cannot match strands whose
number changes).
"""

from __future__ import annotations

import numpy as np

from ..tracer.motion import motion_step_count
from .motion_steps import is_still, resample


def _point_objects(curves) -> np.ndarray:
    """int [P]: the object of each control point of ``curves`` (``CurveSegments``; every point is one of a
    segment's four)."""
    owner = np.full(len(curves.radii), -1, np.int64)
    for k in range(4):
        owner[np.asarray(curves.segments, np.int64) + k] = np.asarray(curves.object, np.int64)
    return owner


def _table(curves) -> np.ndarray:
    return np.column_stack([np.asarray(curves.points, np.float64), np.asarray(curves.radii, np.float64)])


def _frame_indices(names, step_names) -> np.ndarray:
    """int64 [len(step_names) + 1]: the frame's object index of each object of a step's export (-1: none, also
    at the end), matched by name and, for a name given twice (a mesh and its particle hair), by occurrence."""
    where: dict = {}
    for index, name in enumerate(names):
        where.setdefault(name, []).append(index)
    seen: dict = {}
    out = np.full(len(step_names) + 1, -1, np.int64)
    for index, name in enumerate(step_names):
        occurrence = seen[name] = seen.get(name, -1) + 1
        found = where.get(name, ())
        if occurrence < len(found):
            out[index] = found[occurrence]
    return out


def hair_steps(tracer_scene, steps, settings, count, warnings) -> np.ndarray | None:
    """float64 [S, P, 4]: the control points (world) and radii of ``tracer_scene.curves`` at the shutter's ``count``
    time steps, from ``steps`` ((``CurveSegments`` or None, object names) exported at each), matched by object name
    and order, per object as the module says;
    None where no strand moves. ``settings``: object name → (motion blur on, steps, deformation on)."""
    curves = tracer_scene.curves
    if curves is None or not len(curves):
        return None
    names = tracer_scene.object_names
    frame = _table(curves)
    owner = _point_objects(curves)
    table = np.repeat(frame[None], count, axis=0)
    changed = set()
    for s, (step, step_names) in enumerate(steps):
        present = step is not None and len(step) > 0
        step_table = _table(step) if present else np.zeros((0, 4))
        as_frame = _frame_indices(names, step_names)
        step_owner = as_frame[_point_objects(step)] if present else np.zeros(0, np.int64)
        for index in np.unique(owner):
            on, on_step = owner == index, step_owner == index
            if on.sum() == on_step.sum():
                table[s, on] = step_table[on_step]
            else:
                changed.add(int(index))
    for index in np.unique(owner):
        on = owner == index
        name = names[int(index)]
        blur, own_steps, deform = settings.get(name, (True, 1, True))
        if int(index) in changed or not blur or is_still(table[:, on]):
            if int(index) in changed and blur:
                warnings.append(changing_hair_warning(name))
            table[:, on] = frame[on]
            continue
        own = min(motion_step_count(own_steps), count)
        if own < count:
            table[:, on] = resample(table[:, on], own)
        if not deform:
            warnings.append(f"Object '{name}': Motion Blur ▸ Deformation is off, but Prism blurs its hair strands' "
                            "points as they move, so any deformation is blurred too (Cycles blurs only the object's "
                            "transform).")
    return None if is_still(table) else table


def changing_hair_warning(name: str) -> str:
    """The warning for hair whose strands change their number of points during the shutter."""
    return (f"Hair '{name}': its strands change their number of points during the shutter (a modifier adding or "
            "removing strands over time), so Prism cannot follow them: they are rendered still where they are at the "
            "frame, without motion blur.")
