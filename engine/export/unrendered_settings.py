"""Render settings Prism does not model yet: one warning naming the setting and what is rendered
instead, never a silently different image."""

from __future__ import annotations

from .light_path_tricks import light_path_trick_warnings


#: View Layer ▸ Passes switches Prism does not render yet, with Blender's pass names.
UNRENDERED_PASSES = ()  # none at present: Vector and Cryptomatte are written


def unrendered_pass_warnings(view_layer) -> list[str]:
    """One warning per pass ``view_layer`` asks for that Prism does not write."""
    if view_layer is None:
        return []
    return [f"View Layer '{view_layer.name}': the {name} pass is on, but Prism does not write it yet: the pass is "
            "missing from the render result." for switch, name in UNRENDERED_PASSES if getattr(view_layer, switch, False)]


def unrendered_setting_warnings(scene, view_layer=None) -> list[str]:
    """One warning per render setting of ``scene`` (and of the rendered ``view_layer``) that Prism leaves out
    (motion blur's own: ``motion.motion_setting_warnings``)."""
    from .motion import motion_setting_warnings

    return (light_path_trick_warnings(scene) + unrendered_pass_warnings(view_layer)
            + motion_setting_warnings(scene, view_layer))
