"""Motion blur in the camera stage: a path's ray time from the shutter, and a moving camera's pose at it
(``tracer.motion`` builds the tables: the shutter's inverse CDF, the poses at the shutter's steps)."""

from __future__ import annotations

import math

from ..jit import inlined


@inlined
def shutter_time(times, u):
    """Ray time 0..1 for the uniform ``u``: the shutter curve's inverse CDF ``times`` (float64 [M >= 2],
    at M evenly spaced probabilities) read by linear interpolation."""
    x = min(max(u, 0.0), 1.0) * (times.shape[0] - 1)
    j = min(int(x), times.shape[0] - 2)
    f = x - j
    return (1.0 - f) * times[j] + f * times[j + 1]


@inlined
def camera_pose(poses, time):
    """(position (x, y, z), unit quaternion (w, x, y, z)) of a camera at ray time ``time`` from its poses
    at the shutter's S evenly spaced steps (float64 [S, 7]): the position linearly, the rotation by
    spherical linear interpolation (constant angular speed between two steps, as Cycles' decomposed
    motion transforms)."""
    x = min(max(time, 0.0), 1.0) * (poses.shape[0] - 1)
    s = min(int(x), poses.shape[0] - 2)
    f = x - s
    a = poses[s]
    b = poses[s + 1]
    c = ((1.0 - f) * a[0] + f * b[0], (1.0 - f) * a[1] + f * b[1], (1.0 - f) * a[2] + f * b[2])
    cos = a[3] * b[3] + a[4] * b[4] + a[5] * b[5] + a[6] * b[6]  # the export keeps it >= 0
    wa, wb = 1.0 - f, f
    if cos < 0.9995:  # else the two are so close that a linear blend (normalised below) is exact enough
        angle = math.acos(min(max(cos, -1.0), 1.0))
        sin = math.sin(angle)
        wa = math.sin((1.0 - f) * angle) / sin
        wb = math.sin(f * angle) / sin
    q = (wa * a[3] + wb * b[3], wa * a[4] + wb * b[4], wa * a[5] + wb * b[5], wa * a[6] + wb * b[6])
    n = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    return c, (q[0] / n, q[1] / n, q[2] / n, q[3] / n)


@inlined
def quaternion_rotate(q, v):
    """``v`` rotated by the unit quaternion ``q`` (w, x, y, z): v + 2w (u × v) + 2 u × (u × v), u = (x, y, z)."""
    w, ux, uy, uz = q
    tx = 2.0 * (uy * v[2] - uz * v[1])
    ty = 2.0 * (uz * v[0] - ux * v[2])
    tz = 2.0 * (ux * v[1] - uy * v[0])
    return (v[0] + w * tx + uy * tz - uz * ty,
            v[1] + w * ty + uz * tx - ux * tz,
            v[2] + w * tz + ux * ty - uy * tx)
