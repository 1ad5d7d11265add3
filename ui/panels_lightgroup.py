"""Light group of an object (its lights or emissive surfaces) and of the world, as in Cycles: each light
group of the view layer gets a ``Combined_<name>`` pass with the light of its members."""

from __future__ import annotations

import bpy

from ._panel_base import PrismPanel


def _draw_lightgroup(layout, context, owner):
    layout.use_property_split = True
    layout.use_property_decorate = False
    row = layout.row(align=True)
    row.prop_search(owner, "lightgroup", context.view_layer, "lightgroups", text="Light Group", results_are_suggestions=True)
    sub = row.column(align=True)
    sub.enabled = bool(owner.lightgroup) and not any(g.name == owner.lightgroup for g in context.view_layer.lightgroups)
    sub.operator("scene.view_layer_add_lightgroup", icon="ADD", text="").name = owner.lightgroup


class PRISM_PT_object_lightgroup(PrismPanel, bpy.types.Panel):
    bl_label = "Light Group"
    bl_context = "object"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.object is not None

    def draw(self, context):
        _draw_lightgroup(self.layout, context, context.object)


class PRISM_PT_world_lightgroup(PrismPanel, bpy.types.Panel):
    bl_label = "Light Group"
    bl_context = "world"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return super().poll(context) and context.world is not None

    def draw(self, context):
        _draw_lightgroup(self.layout, context, context.world)


register, unregister = bpy.utils.register_classes_factory((PRISM_PT_object_lightgroup, PRISM_PT_world_lightgroup))
