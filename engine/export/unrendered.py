"""Geometry Prism does not render yet: one warning naming the object, never a silent gap."""

from __future__ import annotations

_BY_TYPE: dict[str, str] = {}  # Volume objects render (``volume_objects``); it names what they cannot read


def unrendered_type_warning(obj) -> str | None:
    """The warning for an object whose whole type Prism skips, else None."""
    message = _BY_TYPE.get(obj.type)
    return message.format(name=obj.name) if message else None

