"""The ``velocity`` attribute (m/s, a 3D vector per point) that simulations, Geometry Nodes and caches write on
meshes and point clouds, and the motion it stands for.

Cycles reads it for motion blur and the Vector pass (``attr_create_motion_from_velocity`` in
``intern/cycles/blender/mesh.cpp`` and ``pointcloud.cpp``): where geometry changes its number of vertices or
points from one time to the next (a liquid's surface, particles being born), the velocity is what says how it
moves. Each point moves in a straight line, ``position + velocity × (time - frame time)``, which is what
``velocity_offsets`` gives at the shutter's time steps.
"""

from __future__ import annotations

import numpy as np


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
