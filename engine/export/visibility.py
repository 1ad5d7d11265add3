"""An object's ray visibility, holdout and shadow catcher (Object ▸ Visibility) → ``tracer.visibility`` flag bits."""

from __future__ import annotations

from ..tracer.visibility import (HOLDOUT, RAY_CAMERA, RAY_DIFFUSE, RAY_GLOSSY, RAY_SHADOW, RAY_TRANSMISSION,
                                 SHADOW_CATCHER)

_RAYS = (("visible_camera", RAY_CAMERA), ("visible_shadow", RAY_SHADOW), ("visible_diffuse", RAY_DIFFUSE),
         ("visible_glossy", RAY_GLOSSY), ("visible_transmission", RAY_TRANSMISSION))


def object_flags(obj, view_layer, warnings) -> int:
    """The flags of an (evaluated) object (``warnings``: kept for what Prism may not render as asked)."""
    flags = 0
    for name, bit in _RAYS:
        if getattr(obj, name, True):
            flags |= bit
    holdout = bool(getattr(obj, "is_holdout", False))
    if not holdout and view_layer is not None and hasattr(obj, "holdout_get"):
        try:
            holdout = bool(obj.holdout_get(view_layer=view_layer))  # the collection's Holdout in the view layer
        except (RuntimeError, TypeError):
            pass
    if holdout:
        flags |= HOLDOUT
    if not getattr(obj, "visible_volume_scatter", True) and warnings is not None:
        warnings.append(f"Object '{obj.name}': Ray Visibility ▸ Volume Scatter is off, but Prism has no ray kind for "
                        "rays scattered in a volume: they see it (Cycles' do not).")
    if getattr(obj, "is_shadow_catcher", False):
        flags |= SHADOW_CATCHER  # Object ▸ Visibility ▸ Mask ▸ Shadow Catcher (``tracer.stages.shadow_catcher``)
    return flags
