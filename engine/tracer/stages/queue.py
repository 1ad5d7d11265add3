"""Writing a path's next ray into a queue (the only place rays enter a queue)."""

from __future__ import annotations

import math

from ..jit import inlined


@inlined
def push_ray(state, rays, slot, i, origin, direction):
    """Make (origin, direction) path ``i``'s ray and queue it at ``slot``; returns 1, or 0 (nothing queued,
    the path ends) when the ray is not finite: Embree must never see such rays."""
    if not (math.isfinite(origin[0]) and math.isfinite(origin[1]) and math.isfinite(origin[2])
            and math.isfinite(direction[0]) and math.isfinite(direction[1]) and math.isfinite(direction[2])):
        return 0
    for c in range(3):
        state.origin[i, c] = origin[c]
        state.direction[i, c] = direction[c]
        rays.origin[slot, c] = origin[c]
        rays.direction[slot, c] = direction[c]
    rays.path[slot] = i
    return 1
