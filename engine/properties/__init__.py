"""Settings stored in .blend files: one PropertyGroup per data-block.

The submodules below each have ``register()`` and ``unregister()``; they run in
this order and are undone in reverse.
"""

import bpy

register, unregister = bpy.utils.register_submodule_factory(
    __name__,
    (
        "lens_overlay",
        "farm",
        "scene",
        "camera",
        "light",
        "material",
    ),
)
