"""Small helpers shared by the PropertyGroups: stable dynamic-enum items, subtypes, redraws."""

from __future__ import annotations

import zlib

import bpy

_FLOAT_SUBTYPES = set(bpy.types.FloatProperty.bl_rna.properties["subtype"].enum_items.keys())

# Newer Blender versions show nm / K units for these subtypes; older ones fall back to plain numbers.
WAVELENGTH_SUBTYPE = "WAVELENGTH" if "WAVELENGTH" in _FLOAT_SUBTYPES else "NONE"
TEMPERATURE_SUBTYPE = "COLOR_TEMPERATURE" if "COLOR_TEMPERATURE" in _FLOAT_SUBTYPES else "NONE"


def stable_enum_number(identifier: str, taken: set[int]) -> int:
    """A number for a dynamic enum item that depends only on its identifier.

    A .blend stores an enum as its number, so deriving it from the name keeps a
    saved choice pointing at the same lens or glass when the list grows.
    """
    number = zlib.crc32(identifier.encode("utf-8")) & 0x3FFFFFFF
    while number in taken or number == 0:
        number = (number + 1) & 0x3FFFFFFF
    taken.add(number)
    return number


class DynamicEnumCache:
    """Keeps dynamic enum item strings alive (Blender only borrows them) and rebuilt only on change."""

    def __init__(self, empty_identifier: str, empty_label: str, empty_description: str):
        self._empty = [(empty_identifier, empty_label, empty_description, 0)]
        self._key: tuple | None = None
        self.items: list[tuple[str, str, str, int]] = list(self._empty)

    def update(self, entries: list[tuple[str, str, str]]) -> list[tuple[str, str, str, int]]:
        """Return items for ``entries`` (identifier, label, description), reusing the cached list."""
        key = tuple(entries)
        if key != self._key:
            taken: set[int] = set()
            items = [(ident, label, desc, stable_enum_number(ident, taken)) for ident, label, desc in entries]
            self.items = items or list(self._empty)
            self._key = key
        return self.items


def tag_3d_views_for_redraw(context=None) -> None:
    """Ask every 3D viewport to redraw (the lens overlay reads these settings)."""
    window_manager = getattr(context, "window_manager", None) or bpy.context.window_manager
    if window_manager is None:
        return
    for window in window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


def register_group(cls, id_type, attribute: str, description: str) -> None:
    """Register ``cls`` and hang it on ``id_type`` as ``attribute``."""
    bpy.utils.register_class(cls)
    setattr(id_type, attribute, bpy.props.PointerProperty(type=cls, name="Prism", description=description))


def unregister_group(cls, id_type, attribute: str) -> None:
    """Undo ``register_group``."""
    if hasattr(id_type, attribute):
        delattr(id_type, attribute)
    bpy.utils.unregister_class(cls)
