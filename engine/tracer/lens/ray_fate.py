"""What became of a ray traced through a lens system: the ``fate`` codes (int8) the compiled lens
tracers write and ``LensSystem``, the fans and the camera read.

Its own module so the kernels (``trace_kernel``, ``camera_kernel``) need not import ``system``, which
imports ``trace_kernel`` only when a lens is first traced (numba loads then, not when a lens is read).
"""

FATE_ALIVE = 0
FATE_MISSED = 1  # the ray never meets the surface's sphere (or meets it behind itself)
FATE_BLOCKED = 2  # outside the clear aperture or the aperture stop
FATE_TIR = 3  # total internal reflection
FATE_NAMES = {FATE_ALIVE: "alive", FATE_MISSED: "missed", FATE_BLOCKED: "blocked", FATE_TIR: "TIR"}
