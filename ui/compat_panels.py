"""Show Blender's own Properties panels that apply to Prism (format, output, colour management,
camera lens, object shading, light and material slots) by adding ``"PRISM"`` to their ``COMPAT_ENGINES``."""

from __future__ import annotations

import bpy

ENGINE_ID = "PRISM"

COMPATIBLE_PANELS = frozenset(
    {
        # Output properties
        "RENDER_PT_format",
        "RENDER_PT_format_presets",
        "RENDER_PT_frame_range",
        "RENDER_PT_time_stretching",
        "RENDER_PT_output",
        "RENDER_PT_output_color_management",
        "RENDER_PT_output_pixel_density",
        "RENDER_PT_encoding",
        "RENDER_PT_encoding_video",
        "RENDER_PT_encoding_audio",
        "RENDER_PT_post_processing",
        "RENDER_PT_stamp",
        "RENDER_PT_stamp_note",
        "RENDER_PT_stamp_burn",
        # Render properties
        "RENDER_PT_color_management",
        "RENDER_PT_color_management_display_settings",
        "RENDER_PT_color_management_curves",
        "RENDER_PT_color_management_white_balance",
        "RENDER_PT_color_management_white_balance_presets",
        # Camera data (DOF is drawn by Prism's camera panel with the lens model)
        "DATA_PT_context_camera",
        "CAMERA_PT_presets",
        "CAMERA_PT_safe_areas_presets",
        "DATA_PT_lens",
        "DATA_PT_camera",
        "DATA_PT_camera_display",
        "DATA_PT_camera_display_composition_guides",
        "DATA_PT_camera_safe_areas",
        "DATA_PT_camera_safe_areas_center_cut",
        "DATA_PT_camera_background_image",
        "DATA_PT_custom_props_camera",
        # Object ▸ Shading: Light Linking and Shadow Terminator, as Cycles
        "OBJECT_PT_shading",
        "OBJECT_PT_shadow_terminator",
        # Light data (type, energy and shape are drawn by Prism's light panel)
        "DATA_PT_context_light",
        "DATA_PT_custom_props_light",
        # Material: slots and the node tree's surface
        "EEVEE_MATERIAL_PT_context_material",
        "EEVEE_MATERIAL_PT_surface",
        "EEVEE_MATERIAL_PT_volume",  # the Material Output's Volume: a medium inside the mesh
        "MATERIAL_PT_custom_props",
        # View layer: use for rendering, the Passes parent Prism's pass panels sit in, AOVs, Cryptomatte, light groups
        "VIEWLAYER_PT_layer",
        "VIEWLAYER_PT_filter",  # Environment, Surfaces, Curves, Volumes, Motion Blur: each honoured as Cycles
        "VIEWLAYER_PT_layer_passes",
        "VIEWLAYER_PT_layer_passes_aov",
        "VIEWLAYER_PT_layer_passes_cryptomatte",
        "VIEWLAYER_PT_layer_passes_lightgroups",
        # World
        "WORLD_PT_context_world",
        "EEVEE_WORLD_PT_surface",
        "EEVEE_WORLD_PT_volume",  # the World Output's Volume: fog
        "WORLD_PT_custom_props",
    }
)

_MISSING = object()
# class → its own COMPAT_ENGINES before we touched it (_MISSING when it was inherited)
_patched: dict[type, object] = {}


def compatible_panel_classes() -> list[type]:
    """The registered Blender panel classes in ``COMPATIBLE_PANELS``."""
    return [cls for cls in bpy.types.Panel.__subclasses__() if cls.__name__ in COMPATIBLE_PANELS]


def register():
    for cls in compatible_panel_classes():
        engines = getattr(cls, "COMPAT_ENGINES", None)
        if engines is None or cls in _patched:
            continue
        _patched[cls] = cls.__dict__.get("COMPAT_ENGINES", _MISSING)
        # A new set on this class only: a set shared through a mixin stays untouched.
        cls.COMPAT_ENGINES = set(engines) | {ENGINE_ID}


def unregister():
    for cls, original in _patched.items():
        if original is _MISSING:
            if "COMPAT_ENGINES" in cls.__dict__:
                delattr(cls, "COMPAT_ENGINES")
        else:
            cls.COMPAT_ENGINES = original
    _patched.clear()
