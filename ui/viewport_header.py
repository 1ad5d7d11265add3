"""The pause toggle in the 3D viewport's header while Prism renders the viewport (as Cycles has)."""

from __future__ import annotations

import bpy

from ._panel_base import ENGINE_ID


def draw_pause(self, context) -> None:
    """Appended to ``VIEW3D_HT_header``: a play/pause button in Rendered shading."""
    scene = context.scene
    shading = getattr(context.space_data, "shading", None)
    if context.engine != ENGINE_ID or shading is None or shading.type != "RENDERED":
        return
    paused = scene.prism.preview_pause
    self.layout.prop(scene.prism, "preview_pause", text="", icon="PLAY" if paused else "PAUSE")


def register():
    bpy.types.VIEW3D_HT_header.append(draw_pause)


def unregister():
    bpy.types.VIEW3D_HT_header.remove(draw_pause)
