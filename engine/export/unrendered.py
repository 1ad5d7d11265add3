"""Geometry Prism does not render yet: one warning naming the object, never a silent gap."""

from __future__ import annotations

_BY_TYPE = {
    "VOLUME": "Volume '{name}' is not rendered: Prism has no volume rendering yet, so it renders as empty space.",
}


def unrendered_type_warning(obj) -> str | None:
    """The warning for an object whose whole type Prism skips, else None."""
    message = _BY_TYPE.get(obj.type)
    return message.format(name=obj.name) if message else None


def particle_hair_warnings(obj) -> list[str]:
    """One warning per particle hair system of ``obj`` drawn as strands (Render As: Path)."""
    warnings = []
    for system in getattr(obj, "particle_systems", ()):
        settings = system.settings
        if settings.type == "HAIR" and settings.render_type == "PATH":
            warnings.append(
                f"Object '{obj.name}': particle hair '{system.name}' is not rendered: Prism renders hair as "
                "Curves objects. Convert it with Object ▸ Convert ▸ Curves."
            )
    return warnings
