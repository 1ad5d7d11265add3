"""Clip End of camera rays: a first hit deeper than the camera's Clip End is no hit (the ray sees the
world), as Cycles ends camera rays there. Clip Start moves the camera rays' origins
(``stages.camera.near_clip_distance``), so only the far side is applied here, to the hits Embree found.

Depth is measured along the camera's view axis (perspective and orthographic cameras: Cycles' camera
ray ends at the Clip End plane) or from the camera (panoramas: along the ray). Works on whole queues
of the first bounce, for every camera model (a real lens's rays too).
"""

from __future__ import annotations

import math

import numpy as np

from .stages.camera import ORTHOGRAPHIC, PERSPECTIVE


def clip_far_hits(hit, rays, count: int, camera):
    """``hit`` (triangle int32 [count], t, u, v, as ``Accel.intersect`` returns) with the hits of the
    first ``count`` rays of ``rays`` deeper than ``camera.clip_end_m`` (a ``CameraData``, m) made
    misses (triangle -1)."""
    if not math.isfinite(camera.clip_end_m) or count == 0:
        return hit
    triangle, t, u, v = hit
    found = triangle[:count] >= 0
    origin = rays.origin[:count].astype(np.float64)
    direction = rays.direction[:count].astype(np.float64)
    distance = np.where(found, t[:count], 0.0)[:, None]
    point = origin + distance * direction - camera.origin
    if camera.projection in (PERSPECTIVE, ORTHOGRAPHIC):
        depth_m = point @ -np.asarray(camera.rotation)[:, 2]  # the camera looks down its local -Z
    else:
        depth_m = np.linalg.norm(point, axis=1)
    beyond = found & (depth_m > camera.clip_end_m)
    if not beyond.any():
        return hit
    return np.where(beyond, -1, triangle[:count]).astype(triangle.dtype), t, u, v
