"""An Embree scene of triangle geometry over shared buffers that Prism owns.

    scene = Scene([TriangleGeometry(vertices, triangles)])   # committed, ready for queries
    scene.handle                                           # what kernels pass to rtcIntersect1

Vertices are camera-relative float32 (``geometry.Geometry``), shared with Embree without a copy of
Embree's own, so they stay alive as long as the scene. A geometry may carry several time steps of its
vertices (``rtcSetGeometryTimeStepCount``: Embree interpolates linearly by ray time), the form motion
blur needs; other geometry kinds (curves, points, user geometry) attach the same way, by a class with
``attach(device, scene_handle)``.
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np

from .device import Device, shared_device
from .errors import EmbreeError

# Embree 4 enums (include/embree4/rtcore_*.h)
GEOMETRY_TYPE_TRIANGLE = 0
BUFFER_TYPE_INDEX = 0
BUFFER_TYPE_VERTEX = 1
FORMAT_UINT3 = 0x5003
FORMAT_FLOAT3 = 0x9003
SCENE_FLAG_ROBUST = 1 << 2  # watertight traversal, as embreex builds its scenes: the same hits
BUILD_QUALITY_MEDIUM = 1


@contextmanager
def new_geometry(device: Device, scene_handle, kind: int, created: str, built: str):
    """An Embree geometry of ``kind`` for the block to fill with buffers; committed and attached to
    ``scene_handle`` after it, and released whatever happens (the scene holds its own reference). Embree's
    errors name what failed: ``created`` (e.g. "a sphere geometry") or ``built`` (e.g. "12 spheres")."""
    library = device.library
    geometry = library.rtcNewGeometry(device.handle, kind)
    device.check(f"create {created}")
    try:
        yield geometry
        library.rtcCommitGeometry(geometry)
        library.rtcAttachGeometry(scene_handle, geometry)
        device.check(f"build {built}")
    finally:
        library.rtcReleaseGeometry(geometry)


def _padded_float3(points: np.ndarray) -> np.ndarray:
    """float32 xyz rows followed by one spare float: Embree reads the last vertex with a 16-byte load."""
    flat = np.zeros(points.shape[0] * 3 + 1, np.float32)
    flat[:-1] = np.asarray(points, np.float32).reshape(-1)
    return flat


class TriangleGeometry:
    """A triangle mesh: ``vertices`` float32 [V, 3] (or a sequence of them, one per time step),
    ``triangles`` int [T, 3]. Primitive ids are row numbers of ``triangles``."""

    def __init__(self, vertices, triangles):
        steps = [vertices] if isinstance(vertices, np.ndarray) else list(vertices)
        if not steps or any(s.ndim != 2 or s.shape[1] != 3 or s.shape != steps[0].shape for s in steps):
            raise EmbreeError("triangle geometry needs one or more vertex arrays of shape [V, 3], all alike")
        triangles = np.asarray(triangles)
        if triangles.ndim != 2 or triangles.shape[1] != 3:
            raise EmbreeError(f"triangle geometry needs triangles of shape [T, 3], not {triangles.shape}")
        if len(triangles) and (triangles.min() < 0 or triangles.max() >= steps[0].shape[0]):
            raise EmbreeError("a triangle refers to a vertex that does not exist")
        self.vertex_count = steps[0].shape[0]
        self.triangle_count = triangles.shape[0]
        self._vertices = [_padded_float3(s) for s in steps]
        self._indices = np.ascontiguousarray(triangles, np.uint32)

    @property
    def time_steps(self) -> int:
        return len(self._vertices)

    def attach(self, device: Device, scene_handle) -> None:
        library = device.library
        with new_geometry(device, scene_handle, GEOMETRY_TYPE_TRIANGLE, "a triangle geometry",
                          f"a mesh of {self.triangle_count} triangles") as geometry:
            if self.time_steps > 1:
                library.rtcSetGeometryTimeStepCount(geometry, self.time_steps)
            for step, vertices in enumerate(self._vertices):
                library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_VERTEX, step, FORMAT_FLOAT3,
                                                   vertices.ctypes.data, 0, 12, self.vertex_count)
            library.rtcSetSharedGeometryBuffer(geometry, BUFFER_TYPE_INDEX, 0, FORMAT_UINT3,
                                               self._indices.ctypes.data, 0, 12, self.triangle_count)


class Scene:
    """A committed Embree scene of ``geometries`` (attached in order: geometry ids 0, 1, ...)."""

    def __init__(self, geometries=(), device: Device | None = None):
        self.device = device or shared_device()
        library = self.device.library
        self._geometries = list(geometries)  # keeps the shared buffers alive
        self.handle = library.rtcNewScene(self.device.handle)
        self.device.check("create a scene")
        library.rtcSetSceneFlags(self.handle, SCENE_FLAG_ROBUST)
        library.rtcSetSceneBuildQuality(self.handle, BUILD_QUALITY_MEDIUM)
        try:
            for geometry in self._geometries:
                geometry.attach(self.device, self.handle)
            library.rtcCommitScene(self.handle)
            self.device.check("build the scene's acceleration structure")
        except EmbreeError:
            self.release()
            raise

    def release(self) -> None:
        if self.handle:
            self.device.library.rtcReleaseScene(self.handle)
            self.handle = 0

    def __del__(self):
        self.release()
