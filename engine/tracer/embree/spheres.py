"""Embree sphere points (``RTC_GEOMETRY_TYPE_SPHERE_POINT``): one sphere per point, centre and radius.

    scene = Scene([TriangleGeometry(vertices, triangles), SphereGeometry(points)])

``points`` float32 [S, 4] (x, y, z, radius; camera-relative metres) is shared with Embree without a copy
(``RTC_FORMAT_FLOAT4`` vertex buffer, 16 bytes a point). Primitive ids are rows of ``points``. A hit
reports the unnormalised geometric normal ``Ng`` = hit point - centre (Embree's sphere intersector; its
u, v are 0), which ``queries.closest_hit`` hands on.
"""

from __future__ import annotations

import numpy as np

from .device import Device
from .errors import EmbreeError
from .scene import BUFFER_TYPE_VERTEX, new_geometry

# Embree 4 enums (include/embree4/rtcore_geometry.h, rtcore_buffer.h / rtcore_common.h)
GEOMETRY_TYPE_SPHERE_POINT = 50
FORMAT_FLOAT4 = 0x9004


class SphereGeometry:
    """Spheres: ``points`` float32 [S, 4] (centre x, y, z, radius), S >= 1, radii > 0 and finite."""

    def __init__(self, points):
        points = np.ascontiguousarray(points, np.float32)
        if points.ndim != 2 or points.shape[1] != 4 or not len(points):
            raise EmbreeError(f"sphere geometry needs points of shape [S, 4] (x, y, z, radius), not {points.shape}")
        if not (np.isfinite(points).all() and (points[:, 3] > 0).all()):
            raise EmbreeError("sphere geometry needs finite centres and positive, finite radii")
        self.count = len(points)
        self._points = points

    @property
    def time_steps(self) -> int:
        return 1

    def attach(self, device: Device, scene_handle) -> None:
        with new_geometry(device, scene_handle, GEOMETRY_TYPE_SPHERE_POINT, "a sphere geometry",
                          f"{self.count} spheres") as geometry:
            device.library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_VERTEX, 0, FORMAT_FLOAT4,
                                                      self._points.ctypes.data, 0, 16, self.count)
