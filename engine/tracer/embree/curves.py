"""Embree round Catmull-Rom curves (``RTC_GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE``): hair strands as tubes.

    scene = Scene([TriangleGeometry(vertices, triangles), CurveGeometry(controls, segments)])

``controls`` float32 [P, 4] (x, y, z, radius; camera-relative metres) is the vertex buffer (``RTC_FORMAT_FLOAT4``,
16 bytes a control point), shared with Embree without a copy. ``segments`` [C] is the index buffer
(``RTC_FORMAT_UINT``): the first of the 4 consecutive control points of each segment; Embree's Catmull-Rom
segment runs from the 2nd to the 3rd of them, so a strand's first and last points are repeated once at its
ends (as Cycles' ``BVHEmbree::set_curve_vertex_buffer`` does). Primitive ids are rows of ``segments``.
The surface is a sweep of a sphere of the interpolated radius along the curve (Embree's round mode); a hit
reports the curve parameter of the segment in u (0..1), v = 0 and the unnormalised surface normal in ``Ng``
(Embree's documentation of the curve geometry types), which ``queries.closest_hit`` turns into the curve's
hit code (``tracer.curves.hit_code``).
"""

from __future__ import annotations

import numpy as np

from .device import Device
from .errors import EmbreeError
from .scene import BUFFER_TYPE_INDEX, BUFFER_TYPE_VERTEX, new_geometry

# Embree 4 enums (include/embree4/rtcore_geometry.h, rtcore_common.h)
GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE = 58
FORMAT_UINT = 0x5001
FORMAT_FLOAT4 = 0x9004


class CurveGeometry:
    """Round Catmull-Rom curve segments: ``controls`` float32 [P, 4] (x, y, z, radius), ``segments`` int [C]
    (first control point of each segment; it and the next three must exist), C >= 1, finite controls and
    radii >= 0."""

    def __init__(self, controls, segments):
        controls = np.ascontiguousarray(controls, np.float32)
        segments = np.asarray(segments)
        if controls.ndim != 2 or controls.shape[1] != 4:
            raise EmbreeError(f"curve geometry needs control points of shape [P, 4] (x, y, z, radius), not "
                              f"{controls.shape}")
        if segments.ndim != 1 or not len(segments):
            raise EmbreeError(f"curve geometry needs one or more segments, not an array of shape {segments.shape}")
        if segments.min() < 0 or segments.max() + 3 >= len(controls):
            raise EmbreeError("a curve segment refers to a control point that does not exist")
        if not (np.isfinite(controls).all() and (controls[:, 3] >= 0).all()):
            raise EmbreeError("curve geometry needs finite control points and radii >= 0")
        self.count = len(segments)
        self._controls = controls
        self._segments = np.ascontiguousarray(segments, np.uint32)

    @property
    def time_steps(self) -> int:
        return 1

    def attach(self, device: Device, scene_handle) -> None:
        library = device.library
        with new_geometry(device, scene_handle, GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE, "a curve geometry",
                          f"{self.count} curve segments") as geometry:
            library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_VERTEX, 0, FORMAT_FLOAT4,
                                               self._controls.ctypes.data, 0, 16, len(self._controls))
            library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_INDEX, 0, FORMAT_UINT,
                                               self._segments.ctypes.data, 0, 4, self.count)
