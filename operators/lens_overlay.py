"""Lens overlay actions: switch the viewport overlay on/off, export the diagram as a PNG."""

from __future__ import annotations

import bpy
from bpy.props import IntProperty, StringProperty
from bpy_extras.io_utils import ExportHelper

from ..engine.tracer.errors import PrismInputError


def _draw_module():
    from ..ui import lens_overlay_draw

    return lens_overlay_draw


class PRISM_OT_toggle_lens_overlay(bpy.types.Operator):
    """Show or hide ray fans through the active camera's real lens in the 3D viewport"""

    bl_idname = "prism.toggle_lens_overlay"
    bl_label = "Toggle Lens Overlay"
    bl_options = {"REGISTER"}

    @classmethod
    def poll(cls, context):
        return getattr(getattr(context.scene, "prism", None), "lens_overlay", None) is not None

    def execute(self, context):
        settings = context.scene.prism.lens_overlay
        settings.enabled = not settings.enabled
        _draw_module().sync_handlers()
        return {"FINISHED"}


class PRISM_OT_export_lens_diagram(bpy.types.Operator, ExportHelper):
    """Save the lens overlay (cross-section, ray fans, spot diagram) of the active camera as a PNG"""

    bl_idname = "prism.export_lens_diagram"
    bl_label = "Export Lens Diagram"
    bl_options = {"REGISTER"}

    filename_ext = ".png"
    filter_glob: StringProperty(default="*.png", options={"HIDDEN"})
    width: IntProperty(name="Width", description="Image width in pixels", default=1200, min=64, max=8192)
    height: IntProperty(name="Height", description="Image height in pixels", default=600, min=64, max=8192)

    def execute(self, context):
        from ..ui.lens_overlay_export import write_lens_diagram_png

        try:
            diagram = write_lens_diagram_png(context.scene, self.filepath, self.width, self.height)
        except PrismInputError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report({"INFO"}, f"Lens diagram of '{diagram.name}' saved to {self.filepath}")
        return {"FINISHED"}


_CLASSES = (PRISM_OT_toggle_lens_overlay, PRISM_OT_export_lens_diagram)


register, unregister = bpy.utils.register_classes_factory(_CLASSES)
