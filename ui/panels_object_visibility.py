"""Object ▸ Visibility while Prism renders: Cycles' settings under Cycles' names (Cycles' own panel polls for Cycles
alone). Shadow Catcher, Holdout and Ray Visibility Camera, Diffuse, Glossy, Transmission and Shadow are honoured for
objects; what is not (Volume Scatter; a light's Diffuse, Glossy, Transmission) is named in a warning at export."""

from __future__ import annotations

import bpy

from ._panel_base import PrismPanel

#: Object types with surfaces or light: what Cycles' Mask and Ray Visibility apply to.
_GEOMETRY = {"MESH", "CURVE", "SURFACE", "FONT", "META", "LIGHT", "VOLUME", "POINTCLOUD", "CURVES"}


def _has_geometry_visibility(obj) -> bool:
    return obj is not None and (obj.type in _GEOMETRY or (obj.instance_type == "COLLECTION"
                                                          and obj.instance_collection is not None))


class PRISM_PT_object_visibility(PrismPanel, bpy.types.Panel):
    bl_label = "Visibility"
    bl_context = "object"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.object is not None

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        obj = context.object
        layout.prop(obj, "hide_select", text="Selectable", invert_checkbox=True, toggle=False)
        column = layout.column(heading="Show In")
        column.prop(obj, "hide_viewport", text="Viewports", invert_checkbox=True, toggle=False)
        column.prop(obj, "hide_render", text="Renders", invert_checkbox=True, toggle=False)
        if _has_geometry_visibility(obj):
            column = layout.column(heading="Mask")
            column.prop(obj, "is_shadow_catcher")
            column.prop(obj, "is_holdout")


class PRISM_PT_object_ray_visibility(PrismPanel, bpy.types.Panel):
    bl_label = "Ray Visibility"
    bl_context = "object"
    bl_parent_id = "PRISM_PT_object_visibility"

    @classmethod
    def poll(cls, context):
        return super().poll(context) and _has_geometry_visibility(context.object)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        obj = context.object
        column = layout.column()
        for name, text in (("visible_camera", "Camera"), ("visible_diffuse", "Diffuse"), ("visible_glossy", "Glossy"),
                           ("visible_transmission", "Transmission"), ("visible_volume_scatter", "Volume Scatter")):
            column.prop(obj, name, text=text)
        if obj.type != "LIGHT":
            column.prop(obj, "visible_shadow", text="Shadow")


CLASSES = (PRISM_PT_object_visibility, PRISM_PT_object_ray_visibility)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
