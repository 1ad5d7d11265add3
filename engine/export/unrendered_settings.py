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


def unrendered_setting_warnings(scene) -> list[str]:
    """One warning per render setting of ``scene`` that Prism leaves out."""
    return [message for message in (motion_blur_warning(scene),) if message]
