"""View Layer ▸ Filter as Cycles reads it: what kinds of geometry a view layer renders, and whether it
blurs motion.

Cycles' Blender sync gives a mesh no triangles when Filter ▸ Surfaces (``use_solid``) is off, so neither
its surface nor a volume inside it renders; hair curves are left out when Filter ▸ Curves
(``use_strand``) is off; Volume objects when Filter ▸ Volumes is off; and motion blur needs both Render ▸
Motion Blur and the layer's Filter ▸ Motion Blur. Lights are objects of their own and stay, and so do point
clouds (Cycles' sync has no switch for them yet). Environment (``use_sky``) is read by ``world``.
"""

from __future__ import annotations

from dataclasses import dataclass

#: Object types whose evaluated geometry is a mesh (Text, Curve, Surface and Metaball arrive as meshes).
_SURFACE_TYPES = frozenset({"MESH", "CURVE", "FONT", "SURFACE", "META"})


@dataclass(frozen=True)
class LayerFilter:
    """The switches of one view layer's Filter panel that decide what geometry is exported."""

    surfaces: bool = True  # Filter ▸ Surfaces (use_solid)
    curves: bool = True  # Filter ▸ Curves (use_strand)
    volumes: bool = True  # Filter ▸ Volumes (use_volumes)
    motion_blur: bool = True  # Filter ▸ Motion Blur (use_motion_blur), with Render ▸ Motion Blur
    layer_name: str = ""

    def renders(self, object_type: str) -> bool:
        """Whether an object of ``object_type`` (``Object.type``) contributes geometry to this layer."""
        if object_type in _SURFACE_TYPES:
            return self.surfaces
        if object_type == "CURVES":
            return self.curves
        if object_type == "VOLUME":
            return self.volumes
        return True

    def left_out(self) -> list[str]:
        """The Filter switches that are off and remove geometry (the panel's labels)."""
        return [label for label, on in (("Surfaces", self.surfaces), ("Curves", self.curves)) if not on]


def layer_filter(view_layer) -> LayerFilter:
    """The filter of ``view_layer`` (a ``bpy.types.ViewLayer``), or everything on for None."""
    if view_layer is None:
        return LayerFilter()
    return LayerFilter(
        surfaces=bool(getattr(view_layer, "use_solid", True)),
        curves=bool(getattr(view_layer, "use_strand", True)),
        volumes=bool(getattr(view_layer, "use_volumes", True)),
        motion_blur=bool(getattr(view_layer, "use_motion_blur", True)),
        layer_name=str(getattr(view_layer, "name", "")),
    )
