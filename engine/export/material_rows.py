"""Blender materials → rows of the scene's one list of tracer materials (``MaterialRows``), each exported once.

A material whose volume Density or Emission Strength is driven by nodes gets a row of its own for each piece
of geometry that uses it (the same compiled material): the render bakes them on a grid over the bounds of the
objects of a row (``tracer.media.baked_density``), so objects far apart that share the material each get a
grid over their own bounds instead of sharing one over the space between them.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..tracer.scene import Material
from .cryptomatte_names import material_name
from .materials import DEFAULT_MATERIAL, MaterialExporter
from .mesh_data import AttributeRequest


def _bakes_over_its_mesh(material: Material) -> bool:
    """Whether the render bakes something of the material's volume (its Density, its Emission Strength) on a
    grid over the bounds of the meshes that hold it."""
    return getattr(material.medium, "varies", False) and getattr(material.medium, "voxel_inputs", None) is None


class MaterialRows:
    """``materials`` (tracer materials, the scene's list), with each row's Material ▸ Pass Index
    (``pass_index``) and Cycles' name (``cryptomatte_names``)."""

    def __init__(self, warnings, texture_budget=None, ao_distance=None):
        self.warnings = warnings
        self.exporter = MaterialExporter(warnings, texture_budget=texture_budget, ao_distance=ao_distance)
        self.index: dict = {}
        self.materials: list[Material] = []
        self.uv_pass_slot: int | None = None  # the render UV map's slot when the UV pass is on
        self.pass_index: list[float] = []  # Material ▸ Settings ▸ Pass Index of each material
        self.cryptomatte_names: list[str] = []  # Cycles' name of each material (``cryptomatte_names``)

    def slot_lookup(self, slot_materials: list, owner=None) -> np.ndarray:
        """The rows of the materials of one piece's slots; ``owner`` names the piece (None: a row shared by
        every piece, as a Volume object's material that only computes its density)."""
        return np.asarray([self._of(m, owner) for m in slot_materials] or [self._of(None)], dtype=np.int32)

    def _add(self, key, exported: Material, material) -> int:
        self.index[key] = len(self.materials)
        self.materials.append(exported)
        self.pass_index.append(float(getattr(material, "pass_index", 0.0)) if material is not None else 0.0)
        self.cryptomatte_names.append(material_name(material))
        return self.index[key]

    def _of(self, material, owner=None) -> int:
        made = isinstance(material, Material)  # made by the export itself: a Volume object's grid medium
        key = ("volume", id(material)) if made else (material.name if material is not None else None)
        if key not in self.index:
            self._add(key, material if made else self.exporter.export(material) if material is not None
                      else DEFAULT_MATERIAL, material)
        row = self.index[key]
        if owner is None or made or not _bakes_over_its_mesh(self.materials[row]):
            return row
        own = (key, owner)
        return self.index[own] if own in self.index else self._add(own, replace(self.materials[row]), material)

    def request(self, slot_materials: list) -> AttributeRequest:
        """The per-corner data the materials of one object's slots read (their global slot numbers)."""
        self.slot_lookup(slot_materials)
        slots = self.exporter.slots
        request = AttributeRequest()
        if self.uv_pass_slot is not None:
            request.uvs[self.uv_pass_slot] = ""
        for material in slot_materials:
            if material is None:
                continue
            for kind, name in self.exporter.needs.get(material.original.name, ()):
                if kind == "uv":
                    request.uvs[slots.uv(name)] = name
                elif kind == "attribute":
                    request.attributes[slots.attribute(name)] = name
                elif kind == "tangent":
                    request.tangents[slots.tangent(name)] = name
        return request
