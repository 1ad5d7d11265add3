"""Embree 4 called from compiled code: Prism's own layer over the shared library the embreex wheel ships.

embreex exposes Embree to Python only, one queue per call with the GIL released around it; kernels
cannot call it. This package loads the same ``libembree4`` with ctypes, builds scenes through Embree's C
API and lets numba kernels call ``rtcIntersect1`` / ``rtcOccluded1`` themselves, so a chunk's whole
bounce loop runs in one compiled call (the issue "Every core of an artist's workstation").

- ``library``: finding and loading the library, its C signatures, and the symbols kernels link to.
- ``layout``: ``RTCRayHit`` / ``RTCRay`` as Embree 4 lays them out, declared once.
- ``device``: an Embree device and its errors (``EmbreeError``).
- ``scene``: a scene of triangle geometry over shared camera-relative float32 buffers (vertex time
  steps for motion blur's moving triangles).
- ``spheres``, ``curves``: point clouds' spheres and hair's round Catmull-Rom curves (control point time
  steps for moving hair).
- ``queries``: per-ray compiled functions (closest hit, occlusion) and whole-queue kernels.

embreex's Python API stays the oracle the tests compare this layer with (same hits, same primitive ids).
"""
