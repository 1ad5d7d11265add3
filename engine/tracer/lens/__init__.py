"""Real camera lenses: prescriptions, float64 ray tracing, paraxial optics, focusing,
exit-pupil sampling and the ``RealLensCamera`` the path tracer uses.

bpy-free and import-light: submodules import scipy only inside the functions that need it.
Run ``python -m engine.tracer.lens FILE`` for a lens's first-order data as JSON.
"""
