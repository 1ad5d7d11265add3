"""Values at the shutter's time steps (``export.motion``, ``export.hair_motion``, ``export.point_motion``):
whether they move, an object's own fewer steps spread over the scene's, and the rows of hair and point clouds
matched per object from each step's export to the frame's."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..tracer.motion import motion_step_count


def is_still(steps: np.ndarray) -> bool:
    """Whether ``steps`` [S, ...] holds the same values at every time step."""
    return bool(np.array_equal(steps, np.broadcast_to(steps[:1], steps.shape), equal_nan=True))


def resample(steps: np.ndarray, own: int) -> np.ndarray:
    """``steps`` [S, ...] re-made from its ``own`` evenly spaced steps (a subset of the S, nested), linear
    between them: an object with fewer motion steps moves as Cycles interpolates it."""
    total = len(steps)
    stride = (total - 1) // (own - 1)
    kept = steps[::stride]
    x = np.linspace(0.0, own - 1, total)
    lo = np.minimum(x.astype(int), own - 2)
    f = (x - lo).reshape((-1,) + (1,) * (steps.ndim - 1))
    return (1.0 - f) * kept[lo] + f * kept[lo + 1]


def frame_indices(names, step_names) -> np.ndarray:
    """int64 [len(step_names) + 1]: the frame's object index of each object of a step's export (-1: none, also
    at the end), matched by name and, for a name given twice (a mesh and its particle hair, instances of one
    point cloud), by occurrence."""
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


def matched_steps(names, steps, table, owner) -> list:
    """[(``table(step)`` float64 [M, 4], each row's object as an index into the frame's ``names``, -1: none)] for
    each ``(exported elements or None, object names)`` of ``steps``; ``owner(step)`` gives each row's object in
    its own export's names."""
    matched = []
    for step, step_names in steps:
        if step is None or not len(step):
            matched.append((np.zeros((0, 4)), np.zeros(0, np.int64)))
        else:
            matched.append((table(step), frame_indices(names, step_names)[owner(step)]))
    return matched


@dataclass(frozen=True)
class StepRows:
    """One kind of element (hair control points, points of point clouds) to follow through the shutter:
    ``frame`` float64 [N, 4] (position, world, and radius at the frame), ``owner`` int [N] (each row's object,
    an index into the frame's ``names``), ``steps`` [(float64 [M, 4], int [M] owner as a frame index, -1: none)]
    one per time step, and the warnings for an object whose rows change in number (``changing(name)``) and for
    one moving with Object ▸ Motion Blur ▸ Deformation off (``deforming(name)``); ``unmatched`` float64 [S, N, 4]
    (or None): the rows at each step for an object whose rows change in number (points moved by their velocity),
    NaN where there are none."""

    frame: np.ndarray
    owner: np.ndarray
    steps: list
    changing: Callable[[str], str]
    deforming: Callable[[str], str]
    unmatched: np.ndarray | None = None


def _follows(unmatched, on, finite) -> bool:
    """Whether ``unmatched`` gives every row ``on`` (where the frame's is ``finite``) a finite place at every step."""
    return unmatched is not None and bool(np.isfinite(unmatched[:, on][:, finite[on]]).all())


def object_steps(rows: StepRows, names, settings, count: int, warnings) -> np.ndarray | None:
    """float64 [S, N, 4]: ``rows`` at the shutter's ``count`` time steps, matched per object in order, as Cycles
    matches curve keys and points: Object ▸ Motion Blur off keeps an object still at the frame; fewer Steps than
    the scene's are interpolated between its own; an object whose rows change in number, or stop being finite,
    during the shutter stays still, warned. None where nothing moves. ``settings``: object name → (motion blur on,
    steps, deformation on)."""
    if not len(rows.frame):
        return None
    table = np.repeat(rows.frame[None], count, axis=0)
    frame_finite = np.isfinite(rows.frame).all(axis=1)
    changed, broken = set(), set()
    for s, (step_table, step_owner) in enumerate(rows.steps):
        for index in np.unique(rows.owner):
            on, on_step = rows.owner == index, step_owner == index
            values = step_table[on_step]
            if on.sum() != on_step.sum() and _follows(rows.unmatched, on, frame_finite):
                table[s, on] = rows.unmatched[s, on]
            elif on.sum() != on_step.sum():
                changed.add(int(index))
            elif not np.isfinite(values[frame_finite[on]]).all():
                broken.add(int(index))
            else:
                table[s, on] = values
    table[..., 3] = np.maximum(table[..., 3], 0.0)  # a radius below 0 at a step renders as none
    for index in np.unique(rows.owner):
        on = rows.owner == index
        name = names[int(index)]
        blur, own_steps, deform = settings.get(name, (True, 1, True))
        said = []
        if int(index) in changed | broken or not blur or is_still(table[:, on]):
            if int(index) in changed and blur:
                said.append(rows.changing(name))
            elif int(index) in broken and blur:
                said.append(f"Object '{name}': its positions are not finite (NaN or infinite) at a time step of the "
                            "shutter, so Prism renders it still where it is at the frame, without motion blur.")
            table[:, on] = rows.frame[on]
        else:
            own = min(motion_step_count(own_steps), count)
            if own < count:
                table[:, on] = resample(table[:, on], own)
            if not deform:
                said.append(rows.deforming(name))
        warnings.extend(message for message in said if message not in warnings)  # instances share a name
    return None if is_still(table) else table
