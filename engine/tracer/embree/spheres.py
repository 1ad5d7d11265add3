"""Embree sphere points (``RTC_GEOMETRY_TYPE_SPHERE_POINT``): one sphere per point, centre and radius.

    scene = Scene([TriangleGeometry(vertices, triangles), SphereGeometry(points)])

``points`` float32 [S, 4] (x, y, z, radius; camera-relative metres) is shared with Embree without a copy
(``RTC_FORMAT_FLOAT4`` vertex buffer, 16 bytes a point); a sequence of such arrays gives the spheres that many
time steps (``rtcSetGeometryTimeStepCount``: a vertex buffer per step, centre and radius interpolated linearly
by ray time, as for triangles and curves). Primitive ids are rows of ``points``. A hit reports the
unnormalised geometric normal ``Ng`` = hit point - centre (Embree's sphere intersector; its u, v are 0), which
``queries.closest_hit`` hands on.
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
    """Spheres: ``points`` float32 [S, 4] (centre x, y, z, radius) or a sequence of them, one per time step, S >= 1;
    finite, radii >= 0, and each sphere's positive at some step (a point may shrink away during the shutter)."""

    def __init__(self, points):
        steps = [points] if isinstance(points, np.ndarray) and points.ndim == 2 else list(points)
        steps = [np.ascontiguousarray(step, np.float32) for step in steps]
        first = steps[0] if steps else np.zeros(0, np.float32)
        if first.ndim != 2 or first.shape[1] != 4 or not len(first) or any(s.shape != first.shape for s in steps):
            raise EmbreeError("sphere geometry needs points of shape [S, 4] (x, y, z, radius), the same at every "
                              f"time step, not {[s.shape for s in steps]}")
        largest = np.max([s[:, 3] for s in steps], axis=0)
        if not (all(np.isfinite(s).all() and (s[:, 3] >= 0).all() for s in steps) and (largest > 0).all()):
            raise EmbreeError("sphere geometry needs finite centres and positive, finite radii")
        self.count = len(first)
        self._steps = steps

    @property
    def time_steps(self) -> int:
        return len(self._steps)

    def attach(self, device: Device, scene_handle) -> None:
        library = device.library
        with new_geometry(device, scene_handle, GEOMETRY_TYPE_SPHERE_POINT, "a sphere geometry",
                          f"{self.count} spheres") as geometry:
            if self.time_steps > 1:
                library.rtcSetGeometryTimeStepCount(geometry, self.time_steps)
            for step, points in enumerate(self._steps):
                library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_VERTEX, step, FORMAT_FLOAT4,
                                                   points.ctypes.data, 0, 16, self.count)
