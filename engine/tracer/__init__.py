"""Prism's spectral path tracer: plain numpy, embreex and colour-science.

Never imports bpy, mathutils or gpu. Importing this package is cheap: heavy
modules (colour, scipy, embreex) are imported by the submodules that need them.
"""
