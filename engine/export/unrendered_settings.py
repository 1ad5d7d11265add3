"""Render settings Prism does not model yet: one warning naming the setting and what is rendered
instead, never a silently different image."""

from __future__ import annotations


def motion_blur_warning(scene) -> str | None:
    """The warning for Render Properties ▸ Motion Blur turned on, else None."""
    if not scene.render.use_motion_blur:
        return None
    return (f"Scene '{scene.name}': Render Properties ▸ Motion Blur is on, but Prism has no motion blur yet: the "
            f"image is rendered without motion blur, everything sharp where it stands at frame "
            f"{scene.frame_current + scene.frame_subframe:g}.")


def surfaces_filter_warning(view_layer) -> str | None:
    """The warning for View Layer ▸ Filter ▸ Surfaces turned off (Cycles then renders no surface at all,
    leaving the world), else None."""
    if view_layer is None or getattr(view_layer, "use_solid", True):
        return None
    return (f"View Layer '{view_layer.name}': Filter ▸ Surfaces is off, but Prism does not filter surfaces yet: "
            "every surface is rendered as if it were on (Cycles renders the world alone).")


def unrendered_setting_warnings(scene, view_layer=None) -> list[str]:
    """One warning per render setting of ``scene`` (and of the rendered ``view_layer``) that Prism leaves out."""
    return [message for message in (motion_blur_warning(scene), surfaces_filter_warning(view_layer)) if message]
