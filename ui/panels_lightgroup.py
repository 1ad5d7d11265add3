"""Light group of an object (its lights or emissive surfaces) and of the world, as in Cycles: each light
group of the view layer gets a ``Combined_<name>`` pass with the light of its members."""

from __future__ import annotations

import bpy

from ._panel_base import PrismPanel


class _LightGroupPanel(PrismPanel):
    bl_label = "Light Group"
    bl_options = {"DEFAULT_CLOSED"}
    owner = ""  # the context member whose light group is drawn

    @classmethod
    def poll(cls, context):
        return super().poll(context) and getattr(context, cls.owner, None) is not None


def _draw(layout, context, owner):
    layout.use_property_split = True
    layout.use_property_decorate = False
    row = layout.row(align=True)
    row.prop_search(owner, "lightgroup", context.view_layer, "lightgroups", text="Light Group",
                    results_are_suggestions=True)
    sub = row.column(align=True)
    sub.enabled = bool(owner.lightgroup) and owner.lightgroup not in context.view_layer.lightgroups
    sub.operator("scene.view_layer_add_lightgroup", icon="ADD", text="").name = owner.lightgroup


class PRISM_PT_object_lightgroup(_LightGroupPanel, bpy.types.Panel):
    bl_context = "object"
    owner = "object"

    def draw(self, context):
        _draw(self.layout, context, context.object)


class PRISM_PT_world_lightgroup(_LightGroupPanel, bpy.types.Panel):
    bl_context = "world"
    owner = "world"

    def draw(self, context):
        _draw(self.layout, context, context.world)


CLASSES = (PRISM_PT_object_lightgroup, PRISM_PT_world_lightgroup)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
