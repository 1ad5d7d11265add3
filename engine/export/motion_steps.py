"""Values at the shutter's time steps (``export.motion``, ``export.hair_motion``, ``export.point_motion``,
``export.mesh_motion``): whether they move, an object's own fewer steps spread over the scene's, and the rows of
hair, point clouds and meshes matched per object from each step's export to the frame's."""

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


def matched_steps(names, steps, table, owner, width: int = 4) -> list:
    """[(``table(step)`` float64 [M, ``width``], each row's object as an index into the frame's ``names``, -1: none)]
    for each ``(exported elements or None, object names)`` of ``steps``; ``owner(step)`` gives each row's object in
    its own export's names."""
    matched = []
    for step, step_names in steps:
        if step is None or not len(owner(step)):
            matched.append((np.zeros((0, width)), np.zeros(0, np.int64)))
        else:
            matched.append((table(step), frame_indices(names, step_names)[owner(step)]))
    return matched


@dataclass(frozen=True)
class StepRows:
    """One kind of element (hair control points, points of point clouds, mesh vertices, triangles' corner normals)
    to follow through the shutter: ``frame`` float64 [N, W] (at the frame: position, world, and radius where
    ``has_radius``), ``owner`` int [N] (each row's object, an index into the frame's ``names``), ``steps``
    [(float64 [M, W], int [M] owner as a frame index, -1: none)] one per time step, and the warnings for an object
    whose rows change in number (``changing(name)``) and for one moving with Object ▸ Motion Blur ▸ Deformation off
    (``deforming(name)``); ``by_velocity`` float64 [S, N, W] (or None): the rows at every step of the objects
    that carry a velocity attribute (moved by it), NaN for the others, taken over the steps wherever an object has
    them, as Cycles 4.5 takes the attribute over the steps of meshes, hair and point clouds alike (so also where
    an object's rows change in number)."""

    frame: np.ndarray
    owner: np.ndarray
    steps: list
    changing: Callable[[str], str]
    deforming: Callable[[str], str]
    by_velocity: np.ndarray | None = None
    has_radius: bool = True  # the last of 4 columns is a radius, and a radius below 0 at a step renders as none


def _groups(owner: np.ndarray, size: int):
    """(order, counts, starts): the rows of ``owner`` (object indices < ``size``) sorted by object, keeping their
    order within one (stable), how many each object has, and where each object's run starts in ``order``."""
    order = np.argsort(owner, kind="stable")
    counts = np.bincount(owner, minlength=size)
    return order, counts, np.cumsum(counts) - counts


def _any_per_object(flagged: np.ndarray, owner: np.ndarray, size: int) -> np.ndarray:
    """bool [size]: the objects with a row ``flagged``."""
    return np.bincount(owner[flagged], minlength=size) > 0


def object_steps(rows: StepRows, names, settings, count: int, warnings) -> np.ndarray | None:
    """float64 [S, N, W]: ``rows`` at the shutter's ``count`` time steps, matched per object in order, as Cycles
    matches curve keys, points and vertices: Object ▸ Motion Blur off keeps an object still at the frame; fewer
    Steps than the scene's are interpolated between its own; an object whose rows change in number, or stop being
    finite, during the shutter stays still, warned; one with a velocity attribute moves by it
    (``StepRows.by_velocity``). None where nothing moves. ``settings``: object name → (motion blur on,
    steps, deformation on). Objects are grouped once, so thousands of instances cost no more than one object of
    as many rows."""
    if not len(rows.frame):
        return None
    size = len(names)
    owner = np.asarray(rows.owner, np.int64)
    order, counts, starts = _groups(owner, size)
    rank = np.empty(len(owner), np.int64)  # each row's place among its object's rows
    rank[order] = np.arange(len(owner)) - np.repeat(starts, counts)
    frame_finite = np.isfinite(rows.frame).all(axis=1)
    follows = np.zeros(size, bool)  # objects whose rows ``by_velocity`` places at every step
    if rows.by_velocity is not None:
        follows = ~_any_per_object(frame_finite & ~np.isfinite(rows.by_velocity).all(axis=(0, 2)), owner, size)
    table = np.repeat(rows.frame[None], count, axis=0)
    differs, broken = np.zeros(size, bool), np.zeros(size, bool)
    for s, (step_table, step_owner) in enumerate(rows.steps):
        valid = np.asarray(step_owner) >= 0
        step_order, step_counts, step_starts = _groups(np.asarray(step_owner, np.int64)[valid], size)
        differs |= step_counts != counts
        matched = np.flatnonzero(~differs[owner])  # rows whose object has had as many rows at every step so far
        values = np.asarray(step_table)[valid][step_order[step_starts[owner[matched]] + rank[matched]]]
        table[s, matched] = values
        broken |= _any_per_object(matched[frame_finite[matched] & ~np.isfinite(values).all(axis=1)], owner, size)
    moved = follows[owner]
    if moved.any():
        table[:, moved] = rows.by_velocity[:, moved]
    changed = differs & ~follows
    broken &= ~differs & ~follows
    if rows.has_radius:
        table[..., 3] = np.maximum(table[..., 3], 0.0)
    for index in np.flatnonzero(counts):
        on = order[starts[index]:starts[index] + counts[index]]
        name = names[int(index)]
        blur, own_steps, deform = settings.get(name, (True, 1, True))
        said = []
        if changed[index] or broken[index] or not blur or is_still(table[:, on]):
            if changed[index] and blur:
                said.append(rows.changing(name))
            elif broken[index] and blur:
                said.append(f"Object '{name}': its positions are not finite (NaN or infinite) at a time step of the "
                            "shutter, so Prism renders it still where it is at the frame, without motion blur.")
            table[:, on] = rows.frame[on]
        else:
            own = min(motion_step_count(own_steps), count)
            if own < count:
                table[:, on] = resample(table[:, on], own)
            if not deform and not follows[index]:  # a velocity moves it whatever the switch, as in Cycles
                said.append(rows.deforming(name))
        warnings.extend(message for message in said if message not in warnings)  # instances share a name
    return None if is_still(table) else table
