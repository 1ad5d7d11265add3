"""The rendering side of Prism: the tracer core (``engine.tracer``, bpy-free) and the
Blender glue around it (render engine, session, export, stored settings).

Kept import-light on purpose: nothing here imports bpy, so the tracer and its
command-line tools run without Blender.
"""
