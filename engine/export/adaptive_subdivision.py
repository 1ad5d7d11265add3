"""Object ▸ Subdivision ▸ Adaptive Subdivision (Cycles' experimental feature set): Prism does not dice by
screen size; it renders the mesh Blender evaluates, the Subdivision Surface modifier at its Render levels
(and moves those vertices where a material displaces them)."""

from __future__ import annotations


def adaptive_subdivision_warning(obj, scene) -> str | None:
    """The warning for ``obj`` when Cycles would dice it adaptively, else None."""
    if not getattr(getattr(obj, "cycles", None), "use_adaptive_subdivision", False):
        return None
    if getattr(getattr(scene, "cycles", None), "feature_set", "SUPPORTED") != "EXPERIMENTAL":
        return None  # Cycles itself ignores the switch outside its experimental feature set
    return (f"Object '{obj.name}': Adaptive Subdivision is not supported; Prism renders the Subdivision Surface "
            "modifier at its Render levels (and displaces those vertices) instead of dicing by screen size.")
