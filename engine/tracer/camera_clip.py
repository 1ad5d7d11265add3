"""Clip End of camera rays: a first hit deeper than the camera's Clip End is no hit (the ray sees the
world), as Cycles ends camera rays there. Clip Start moves the camera rays' origins
(``stages.camera.near_clip_distance``), so only the far side is applied here, to the hits Embree found.

Depth is measured along the camera's view axis (perspective and orthographic cameras: Cycles' camera
ray ends at the Clip End plane) or from the camera (panoramas: along the ray). Applied to the first
bounce's queue, for every camera model (a real lens's rays too): by the compiled bounce loop
(``stages.bounce_loop``) and, through ``clip_far_hits``, by the stepwise one.
"""

from __future__ import annotations

import math

from .jit import kernel
from .stages.camera import ORTHOGRAPHIC, PERSPECTIVE
from .state import HitRecord


@kernel
def clip_far_hits_kernel(camera, rays, count, hits):
    """Make the hits of rays ``0 .. count`` of ``rays`` (a ``state.RayQueue``) deeper than
    ``camera.clip_end_m`` (a ``stages.camera.CameraData``, m) misses in ``hits`` (a ``state.HitRecord``)."""
    if not math.isfinite(camera.clip_end_m):
        return
    along_axis = camera.projection == PERSPECTIVE or camera.projection == ORTHOGRAPHIC
    r = camera.rotation
    for j in range(count):
        if hits.triangle[j] < 0:
            continue
        t = float(hits.t[j])
        p = (rays.origin[j, 0] + t * rays.direction[j, 0] - camera.origin[0],
             rays.origin[j, 1] + t * rays.direction[j, 1] - camera.origin[1],
             rays.origin[j, 2] + t * rays.direction[j, 2] - camera.origin[2])
        if along_axis:  # the camera looks down its local -Z
            depth_m = -(p[0] * r[0, 2] + p[1] * r[1, 2] + p[2] * r[2, 2])
        else:
            depth_m = math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
        if depth_m > camera.clip_end_m:
            hits.triangle[j] = -1


def clip_far_hits(hit, rays, count: int, camera):
    """``hit`` (triangle int32 [count], t, u, v, as ``Accel.intersect`` returns) with the hits of the
    first ``count`` rays of ``rays`` deeper than ``camera.clip_end_m`` made misses (in place)."""
    record = hit if isinstance(hit, HitRecord) else HitRecord(*hit)
    clip_far_hits_kernel(camera, rays, count, record)
    return record
