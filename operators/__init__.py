"""User actions (operators) that Prism adds to Blender.

The submodules below each have ``register()`` and ``unregister()``; they run in
this order and are undone in reverse.
"""

import bpy

register, unregister = bpy.utils.register_submodule_factory(
    __name__,
    (
        "lens_overlay",
        "autofocus",
        "farm_submit",
    ),
)
