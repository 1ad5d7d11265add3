"""Prism's spectral path tracer: numba kernels, Embree 4 called from them (``embree``, the library the
embreex wheel ships), colour-science for colour data.

Never imports bpy, mathutils or gpu. Importing this package is cheap: heavy
modules (numba, colour, scipy, embreex) are imported by the submodules that need them.
"""
