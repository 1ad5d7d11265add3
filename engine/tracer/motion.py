"""Motion blur as Blender and Cycles define it: the shutter, and the scene at evenly spaced times in it.

A path's *ray time* τ runs 0..1 over the open shutter (the form Embree reads in ``RTCRay.time``); the
export evaluates the scene at S times ``shutter_start + step/(S-1) · shutter_length`` (Cycles' motion
steps: S = 2^(steps-1)·2 + 1, 3 by default), and the tracer interpolates linearly between the two
steps around τ·(S-1): vertices (as Embree does), corner normals, and the camera's position, with its
rotation by spherical interpolation of quaternions (as Cycles interpolates decomposed transforms).

The shutter curve (Render ▸ Motion Blur ▸ Shutter Curve: how open the shutter is over its time) makes
τ follow that curve's density: ``shutter_times(curve)`` tabulates its inverse CDF, which the camera
stage reads at a uniform sample (a flat curve gives τ = u).

``Motion`` holds the geometry's steps; the camera's live on ``scene.Camera`` (``shutter_times``,
``motion_to_world``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Entries of the shutter's inverse-CDF table for a curve that is not flat (its resolution in time).
SHUTTER_TABLE_SIZE = 256


@dataclass
class Motion:
    """The scene's geometry at the shutter's S time steps: ``vertices`` float64 [S, V, 3] (world, m, the
    same vertices as ``Scene.vertices`` in the same order; None where no triangle moves), ``corner_normals``
    float32 [S, T, 3, 3] (or None for flat shading), ``curves`` float64 [S, P, 4] (the hair strands' control
    points, world, and radii, in the order of ``Scene.curves``; None where no strand moves) and ``points`` float64
    [S, N, 4] (the point clouds' centres, world, and radii, in the order of ``Scene.points``; None where no point
    moves)."""

    vertices: np.ndarray | None
    corner_normals: np.ndarray | None = None
    curves: np.ndarray | None = None
    points: np.ndarray | None = None


def motion_step_count(steps: int) -> int:
    """Cycles' number of time steps for Object ▸ Motion Blur ▸ Steps ``steps``: odd, so one falls on the
    shutter's middle, and nested (2^(steps-1)·2 + 1: 3, 5, 9, ...) so objects with different step
    counts share sample times."""
    return (2 << (max(int(steps), 1) - 1)) + 1


def shutter_times(curve_values) -> np.ndarray:
    """The inverse CDF of the shutter's openness ``curve_values`` (float [N >= 2], sampled evenly over the
    shutter, non-negative), as float64 [M] times 0..1 at M evenly spaced probabilities 0..1: τ(u) is
    read by linear interpolation. A flat curve (or one that is zero everywhere) gives [0, 1], τ = u."""
    values = np.clip(np.asarray(curve_values, np.float64), 0.0, None)
    if values.max() <= 0.0 or np.allclose(values, values[0]):
        return np.array([0.0, 1.0])
    x = np.linspace(0.0, 1.0, len(values))
    segments = 0.5 * (values[1:] + values[:-1]) * np.diff(x)  # trapezoids of a piecewise-linear openness
    cdf = np.concatenate([[0.0], np.cumsum(segments)]) / segments.sum()
    u = np.linspace(0.0, 1.0, SHUTTER_TABLE_SIZE)
    return np.interp(u, cdf, x)


def rotation_quaternion(rotation: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a 3x3 rotation matrix (Shepperd's method: the largest of the four
    squared components is taken first, so it stays accurate near 180°)."""
    m = np.asarray(rotation, np.float64)
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    candidates = [trace, m[0, 0], m[1, 1], m[2, 2]]
    k = int(np.argmax(candidates))
    if k == 0:
        s = 2.0 * np.sqrt(1.0 + trace)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif k == 1:
        s = 2.0 * np.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [(m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif k == 2:
        s = 2.0 * np.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s]
    q = np.asarray(q)
    return q / np.linalg.norm(q)


def camera_poses(camera_to_world_steps, origin_world) -> np.ndarray:
    """float64 [S, 7]: per time step the camera's position relative to ``origin_world`` (m) and its
    rotation as a unit quaternion (w, x, y, z), each on the same side as the one before (so the
    interpolation takes the short way round). The matrices' scale is removed column by column."""
    poses = []
    previous = None
    for matrix in np.asarray(camera_to_world_steps, np.float64):
        linear = matrix[:3, :3] / np.linalg.norm(matrix[:3, :3], axis=0)
        q = rotation_quaternion(linear)
        if previous is not None and float(q @ previous) < 0.0:
            q = -q
        previous = q
        poses.append(np.concatenate([matrix[:3, 3] - np.asarray(origin_world, np.float64), q]))
    return np.ascontiguousarray(poses, np.float64)
