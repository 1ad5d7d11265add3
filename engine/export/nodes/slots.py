"""Which mesh data the compiled materials read: UV maps, colour and other attributes, UV tangents, object
data. Programs refer to them by slot number; the mesh export fills each slot of each mesh by name
(``mesh_attributes``), so only what some material reads is exported."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class AttributeSlots:
    uv_names: list = field(default_factory=list)  # "" = each mesh's active render UV map
    attribute_names: list = field(default_factory=list)  # "" = each mesh's active colour attribute
    tangent_names: list = field(default_factory=list)  # UV maps whose tangents are read
    objects: bool = False  # object coordinates, generated coordinates or object info

    @staticmethod
    def _slot(names, name):
        if name not in names:
            names.append(name)
        return names.index(name)

    def uv(self, name: str = "") -> int:
        return self._slot(self.uv_names, name or "")

    def attribute(self, name: str = "") -> int:
        return self._slot(self.attribute_names, name or "")

    def tangent(self, name: str = "") -> int:
        return self._slot(self.tangent_names, name or "")

    def need_objects(self) -> None:
        self.objects = True

    @property
    def any(self) -> bool:
        return bool(self.uv_names or self.attribute_names or self.tangent_names or self.objects)
