"""Panels and viewport drawing.

The submodules below each have ``register()`` and ``unregister()``; they run in
this order and are undone in reverse.
"""

import bpy

register, unregister = bpy.utils.register_submodule_factory(
    __name__,
    (
        "compat_panels",
        "spectral_plot",
        "panels_render",
        "panel_farm",
        "panels_camera",
        "panels_light",
        "panels_material",
        "panels_lightgroup",
        "panels_object_visibility",
        "lens_overlay_draw",
        "lens_overlay_panel",
        "viewport_header",
    ),
)
