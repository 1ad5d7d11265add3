"""Render settings Prism does not model yet: one warning naming the setting and what is rendered
instead, never a silently different image."""

from __future__ import annotations

from .light_path_tricks import light_path_trick_warnings


def stereo_warning(scene) -> str | None:
    """The warning for Output ▸ Stereoscopy (multi-view) turned on, else None: Prism renders one view."""
    render = scene.render
    if not render.use_multiview:
        return None
    views = [view.name for view in render.views if view.use] if render.views_format == "MULTIVIEW" else [
        "left", "right"]
    if len(views) < 2:
        return None
    others = ", ".join(f"'{name}'" for name in views[1:])
    return (f"Scene '{scene.name}': Output ▸ Stereoscopy is on, but Prism renders one view: '{views[0]}' gets the "
            f"image of the scene camera itself (no eye offset), and {others} stay{'s' if len(views) == 2 else ''} "
            "black (Cycles renders every view).")


#: View Layer ▸ Passes switches Prism does not render yet, with Blender's pass names.
UNRENDERED_PASSES = (("use_pass_vector", "Vector"), ("use_pass_cryptomatte_object", "CryptoObject"),
                     ("use_pass_cryptomatte_material", "CryptoMaterial"),
                     ("use_pass_cryptomatte_asset", "CryptoAsset"))


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

    prism = getattr(scene, "prism", None)
    return [message for message in [stereo_warning(scene)] if message] + (
        light_path_trick_warnings(scene) + unrendered_pass_warnings(view_layer)) + motion_setting_warnings(
        scene, getattr(prism, "light_tracing", "AUTO"), view_layer)
