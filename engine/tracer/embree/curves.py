"""Embree round Catmull-Rom curves (``RTC_GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE``): hair strands as tubes.

    scene = Scene([TriangleGeometry(vertices, triangles), CurveGeometry(controls, segments)])

``controls`` float32 [P, 4] (x, y, z, radius; camera-relative metres) is the vertex buffer (``RTC_FORMAT_FLOAT4``,
16 bytes a control point), shared with Embree without a copy; a sequence of such arrays gives the curves that
many time steps (``rtcSetGeometryTimeStepCount``: a vertex buffer per step, interpolated linearly by ray time,
as for triangles). ``segments`` [C] is the index buffer
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
    """Round Catmull-Rom curve segments: ``controls`` float32 [P, 4] (x, y, z, radius) or a sequence of them,
    one per time step, ``segments`` int [C] (first control point of each segment; it and the next three must
    exist), C >= 1, finite controls and radii >= 0."""

    def __init__(self, controls, segments):
        steps = [controls] if isinstance(controls, np.ndarray) and controls.ndim == 2 else list(controls)
        steps = [np.ascontiguousarray(step, np.float32) for step in steps]
        controls = steps[0] if steps else np.zeros(0, np.float32)
        segments = np.asarray(segments)
        if not steps or any(s.ndim != 2 or s.shape[1] != 4 or s.shape != controls.shape for s in steps):
            raise EmbreeError(f"curve geometry needs control points of shape [P, 4] (x, y, z, radius), the same at "
                              f"every time step, not {[s.shape for s in steps]}")
        if segments.ndim != 1 or not len(segments):
            raise EmbreeError(f"curve geometry needs one or more segments, not an array of shape {segments.shape}")
        if segments.min() < 0 or segments.max() + 3 >= len(controls):
            raise EmbreeError("a curve segment refers to a control point that does not exist")
        if not all(np.isfinite(s).all() and (s[:, 3] >= 0).all() for s in steps):
            raise EmbreeError("curve geometry needs finite control points and radii >= 0")
        self.count = len(segments)
        self._steps = steps
        self._segments = np.ascontiguousarray(segments, np.uint32)

    @property
    def time_steps(self) -> int:
        return len(self._steps)

    def attach(self, device: Device, scene_handle) -> None:
        library = device.library
        with new_geometry(device, scene_handle, GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE, "a curve geometry",
                          f"{self.count} curve segments") as geometry:
            if self.time_steps > 1:
                library.rtcSetGeometryTimeStepCount(geometry, self.time_steps)
            for step, controls in enumerate(self._steps):
                library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_VERTEX, step, FORMAT_FLOAT4,
                                                   controls.ctypes.data, 0, 16, len(controls))
            library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_INDEX, 0, FORMAT_UINT,
                                               self._segments.ctypes.data, 0, 4, self.count)
