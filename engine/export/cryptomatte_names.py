"""The names Cryptomatte ids are made of, as Cycles' sync names them: an object by its own name (an
instance by the instanced object's), its asset by the name of its topmost parent (itself when it has
none), a material by its name, and a slot without material "default_surface" (Cycles' default shader)."""

from __future__ import annotations

from ..tracer.cryptomatte import DEFAULT_MATERIAL_NAME


def asset_name(obj) -> str:
    """The name of ``obj``'s topmost parent, or its own without a parent."""
    while obj.parent is not None:
        obj = obj.parent
    return obj.name


def material_name(material) -> str:
    return material.name if material is not None else DEFAULT_MATERIAL_NAME
