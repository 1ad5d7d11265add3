"""``Camera.prism``: which lens model the camera uses.

Depth of field (the checkbox, focus distance or object, f-stop, blades, rotation, ratio) is Blender's own
``camera.dof``.
"""

import importlib
from pathlib import Path

import bpy
from bpy.props import EnumProperty, StringProperty

from ._common import DynamicEnumCache, register_group, stable_enum_number, unregister_group
from .file_path import BLEND_RELATIVE_PATH_OPTIONS

LENS_DIRECTORY = Path(__file__).resolve().parents[2] / "lenses"
DEFAULT_BUNDLED_LENS = "double_gauss_50mm"

LENS_MODEL_ITEMS = [
    (
        "PINHOLE",
        "Blender camera",
        "Blender's camera as Cycles renders it: perspective, orthographic or panoramic, in focus everywhere "
        "unless its Depth of Field box is checked",
        0,
    ),
    ("THIN_LENS", "Thin lens", "An ideal thin lens, always: depth of field from the f-stop and focus distance", 1),
    (
        "REAL_LENS",
        "Real lens",
        "Trace every element of a lens prescription: chromatic aberration, vignetting, distortion",
        2,
    ),
]

LENS_SOURCE_ITEMS = [
    ("BUNDLED", "Bundled", "A lens prescription shipped with Prism", 0),
    ("FILE", "File", "A lens prescription file (.lens) on disk", 1),
]

_bundled_cache = DynamicEnumCache("NONE", "No bundled lenses", "No lens prescriptions were found in Prism's lenses folder")


def _entry_of(item) -> tuple[str, str, str] | None:
    """(identifier, label, description) of one ``bundled_lenses()`` entry, whatever its shape."""
    if isinstance(item, (str, Path)):
        name = Path(item).stem if str(item).endswith(".lens") else str(item)
        return name, name, f"Bundled lens {name}"
    if isinstance(item, (tuple, list)) and item:
        name = Path(str(item[0])).stem if str(item[0]).endswith(".lens") else str(item[0])
        label = str(item[1]) if len(item) > 1 and isinstance(item[1], str) else name
        return name, label, f"Bundled lens {label}"
    name = getattr(item, "name", None)
    if name:
        label = str(getattr(item, "title", None) or getattr(item, "label", None) or name)
        return str(name), label, str(getattr(item, "description", None) or f"Bundled lens {label}")
    return None


def bundled_lens_entries() -> list[tuple[str, str, str]]:
    """The bundled lenses as (identifier, label, description), from the catalogue when it exists."""
    try:
        catalogue = importlib.import_module("..tracer.lens.catalogue", __package__)
        entries = [e for e in map(_entry_of, catalogue.bundled_lenses()) if e]
    except Exception:  # noqa: BLE001 - an enum callback must never raise; fall back to the folder
        entries = [(p.stem, p.stem, f"Bundled lens {p.name}") for p in sorted(LENS_DIRECTORY.glob("*.lens"))]
    return sorted(set(entries))


def _bundled_lens_items(self, context):
    return _bundled_cache.update(bundled_lens_entries())


class PrismCameraSettings(bpy.types.PropertyGroup):
    """Prism settings of a camera."""

    lens_model: EnumProperty(
        name="Lens Model",
        description="How rays leave the camera",
        items=LENS_MODEL_ITEMS,
        default="PINHOLE",
    )
    lens_source: EnumProperty(
        name="Lens Source",
        description="Where the real lens prescription comes from",
        items=LENS_SOURCE_ITEMS,
        default="BUNDLED",
    )
    bundled_lens: EnumProperty(
        name="Lens",
        description="Lens prescription shipped with Prism",
        items=_bundled_lens_items,
        default=stable_enum_number(DEFAULT_BUNDLED_LENS, set()),
    )
    lens_file: StringProperty(
        name="Lens File",
        description="Path of a lens prescription file (.lens)",
        default="",
        subtype="FILE_PATH",
        options=BLEND_RELATIVE_PATH_OPTIONS,
    )

    def lens_path(self) -> str | None:
        """Absolute path of the chosen real lens prescription, or None when none is chosen."""
        if self.lens_source == "FILE":
            return bpy.path.abspath(self.lens_file) if self.lens_file else None
        name = self.bundled_lens
        if not name or name == "NONE":
            return None
        try:
            catalogue = importlib.import_module("..tracer.lens.catalogue", __package__)
            path = catalogue.bundled_lens_path(name)
            return str(path)
        except (ImportError, AttributeError):
            return str(LENS_DIRECTORY / f"{name}.lens")


def register():
    register_group(PrismCameraSettings, bpy.types.Camera, "prism", "Prism camera settings")


def unregister():
    unregister_group(PrismCameraSettings, bpy.types.Camera, "prism")
