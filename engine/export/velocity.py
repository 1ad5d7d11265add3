"""The ``velocity`` attribute (m/s, a 3D vector per point) that simulations, Geometry Nodes and caches write on
meshes and point clouds, and the motion it stands for.

Cycles reads it for motion blur and the Vector pass (``attr_create_motion_from_velocity`` in
``intern/cycles/blender/mesh.cpp`` and ``pointcloud.cpp``): where geometry changes its number of vertices or
points from one time to the next (a liquid's surface, particles being born), the velocity is what says how it
moves. Each point moves in a straight line, ``position + velocity × (time - frame time)``, which is what
``velocity_offsets`` gives at the shutter's time steps; an object whose transform moves too carries those points
along (``moved_positions``), as Cycles adds the object's motion to its geometry's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .motion_steps import frame_indices


def read_velocity(data, count: int) -> np.ndarray | None:
    """float64 [count, 3]: the point-domain 3D-vector attribute ``velocity`` of ``data`` (a ``bpy.types.Mesh`` or
    ``PointCloud`` with ``count`` vertices or points, object space), or None without one."""
    attribute = data.attributes.get("velocity")
    if attribute is None or attribute.domain != "POINT" or attribute.data_type != "FLOAT_VECTOR":
        return None
    if len(attribute.data) != count:
        return None
    values = np.empty(count * 3, np.float32)
    attribute.data.foreach_get("vector", values)
    return values.reshape(-1, 3).astype(np.float64)


def placed_velocity(velocity: np.ndarray | None, count: int, matrices: np.ndarray) -> np.ndarray:
    """float64 [K*count, 3]: ``velocity`` (float64 [count, 3], object space; None: none) turned into world space by
    each of ``matrices`` [K, 4, 4] (their linear part: a velocity has no position); NaN without one."""
    if velocity is None:
        return np.full((len(matrices) * count, 3), np.nan)
    return np.einsum("kij,pj->kpi", matrices[:, :3, :3], velocity).reshape(-1, 3)


def velocity_offsets(velocity, seconds) -> np.ndarray | None:
    """float64 [S, N, 3]: how far each point's ``velocity`` (float64 [N, 3], m/s, world; NaN: none) carries it at
    each time step, ``seconds`` [S] from the frame; None without velocities."""
    if velocity is None or seconds is None:
        return None
    return np.asarray(seconds, np.float64)[:, None, None] * np.asarray(velocity, np.float64)[None]


@dataclass(frozen=True)
class Transforms:
    """Each object's instance transforms at the frame and at the shutter's time steps: ``names`` and ``frame`` (per
    object, float64 [K, 4, 4]) of the frame's export, and per step ``steps`` [(its objects' matrices, its object
    names)], so a step's object is found by name and occurrence (``motion_steps.frame_indices``)."""

    names: list
    frame: list
    steps: list


def _relative(frame, step) -> np.ndarray | None:
    """float64 [K, 4, 4]: the instances' transforms ``step`` relative to ``frame`` (both [K, 4, 4]); None where the
    step has another number of instances, or a transform does not invert."""
    if step is None or np.shape(step) != np.shape(frame):
        return None
    try:
        return np.asarray(step, np.float64) @ np.linalg.inv(np.asarray(frame, np.float64))
    except np.linalg.LinAlgError:
        return None


def moved_positions(positions, drift, owner, transforms: Transforms | None) -> np.ndarray | None:
    """float64 [S, N, 3]: ``positions`` [N, 3] (world, at the frame) moved by ``drift`` [S, N, 3]
    (``velocity_offsets``; NaN where a row has no velocity) and carried by their object's transform at each step
    relative to the frame's, instance by instance, as Cycles adds an object's transform motion to the motion its
    velocity attribute gives (an object's rows are its instances' blocks of equal size, in order; ``owner`` [N]
    each row's object); None without drift."""
    if drift is None:
        return None
    moved = np.asarray(positions, np.float64)[None] + drift
    if transforms is None:
        return moved
    owner = np.asarray(owner, np.int64)
    carried = np.unique(owner[np.isfinite(drift).all(axis=(0, 2))])
    if not len(carried):
        return moved
    found = [frame_indices(transforms.names, names)[:-1] for _, names in transforms.steps]
    for index in carried:
        rows = np.flatnonzero(owner == index)
        blocks = len(transforms.frame[index])
        if not blocks or len(rows) % blocks:
            continue
        for s, ((matrices, _), where) in enumerate(zip(transforms.steps, found)):
            at = np.flatnonzero(where == index)
            relative = _relative(transforms.frame[index], matrices[at[0]] if len(at) else None)
            if relative is None:
                continue
            block = moved[s, rows].reshape(blocks, -1, 3)
            block = np.einsum("kij,kpj->kpi", relative[:, :3, :3], block) + relative[:, None, :3, 3]
            moved[s, rows] = block.reshape(-1, 3)
    return moved
