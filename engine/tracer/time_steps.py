"""Position-and-radius rows given at the shutter's time steps (hair control points, point-cloud spheres), read at a
ray's time the way Embree reads its vertex buffers: linear between the two steps around it."""

from __future__ import annotations

from .jit import kernel


@kernel
def row_at(frame, steps, k, time):
    """(x, y, z, radius) of row ``k`` at ray time ``time`` (0..1 over the shutter) of ``steps`` [S, N, 4]; of
    ``frame`` [N, 4] where there are no steps (nothing moves) or ``time`` < 0 (``geometry.FRAME_TIME``)."""
    if steps.shape[0] == 0 or time < 0.0:
        return float(frame[k, 0]), float(frame[k, 1]), float(frame[k, 2]), float(frame[k, 3])
    x = min(time, 1.0) * (steps.shape[0] - 1)
    s = min(int(x), steps.shape[0] - 2)
    f = x - s
    return ((1.0 - f) * float(steps[s, k, 0]) + f * float(steps[s + 1, k, 0]),
            (1.0 - f) * float(steps[s, k, 1]) + f * float(steps[s + 1, k, 1]),
            (1.0 - f) * float(steps[s, k, 2]) + f * float(steps[s + 1, k, 2]),
            (1.0 - f) * float(steps[s, k, 3]) + f * float(steps[s + 1, k, 3]))
