"""Writing a path's next ray, or a light sample's shadow ray, into a queue (the only places rays enter one)."""

from __future__ import annotations

import math

from ..jit import inlined


@inlined
def _finite(origin, direction):
    """Whether a ray is finite: Embree must never see one that is not."""
    return (math.isfinite(origin[0]) and math.isfinite(origin[1]) and math.isfinite(origin[2])
            and math.isfinite(direction[0]) and math.isfinite(direction[1]) and math.isfinite(direction[2]))


@inlined
def push_ray(state, rays, slot, i, origin, direction):
    """Make (origin, direction) path ``i``'s ray and queue it at ``slot``; returns 1, or 0 (nothing queued,
    the path ends) when the ray is not finite: Embree must never see such rays."""
    if not _finite(origin, direction):
        return 0
    for c in range(3):
        state.origin[i, c] = origin[c]
        state.direction[i, c] = direction[c]
        rays.origin[slot, c] = origin[c]
        rays.direction[slot, c] = direction[c]
    rays.path[slot] = i
    return 1


@inlined
def queue_shadow(shadows, slot, i, origin, direction, distance, group, medium, blockers, crossable):
    """Queue path ``i``'s shadow ray from ``origin`` along ``direction`` over ``distance`` toward light group
    ``group`` at ``slot`` of ``shadows``, in ``medium`` (-1: none), blocked by the objects of the blocker
    sets ``blockers`` (``light_linking.ALL_SETS``: by everything) and by any cut-out or film past the first
    ``crossable``; returns 1, or 0 (nothing queued) when the ray is not finite or has no length. Its contribution
    is written by the caller."""
    if not (_finite(origin, direction) and distance > 0.0):
        return 0
    rays = shadows.rays
    for c in range(3):
        rays.origin[slot, c] = origin[c]
        rays.direction[slot, c] = direction[c]
        shadows.origin[slot, c] = origin[c]
        shadows.direction[slot, c] = direction[c]
    rays.tmax[slot] = distance
    shadows.distance[slot] = distance
    shadows.group[slot] = group
    shadows.medium[slot] = medium
    shadows.blockers[slot] = blockers
    shadows.crossable[slot] = crossable
    rays.path[slot] = i
    return 1
