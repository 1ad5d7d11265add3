"""Render properties ▸ Farm: submit the scene to a Flamenco render farm (``prism.farm_submit``)."""

from __future__ import annotations

import bpy

from ..operators.farm_submit import job_summary
from ..operators import online_access
from ._panel_base import PrismPanel, error_label


class PRISM_PT_farm(PrismPanel, bpy.types.Panel):
    """Flamenco Manager, chunks per frame, output on shared storage, and the submit button."""

    bl_label = "Farm"
    bl_context = "render"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        scene = context.scene
        farm = scene.prism.farm
        column = layout.column()
        column.prop(farm, "manager_url")
        column.prop(farm, "job_name", placeholder="File name")
        column.prop(farm, "priority")
        column = layout.column()
        column.prop(farm, "chunks")
        column.prop(farm, "output_path")
        column.prop(farm, "render_script")
        try:
            layout.label(text=job_summary(scene), icon="INFO")
        except ValueError as error:
            error_label(layout, str(error))
        online = online_access.online_access_allowed()
        if not online:  # say why the button is greyed out, and where to turn it on
            error_label(layout, online_access.OFFLINE_MESSAGE)
        row = layout.row()
        row.enabled = online
        row.operator("prism.farm_submit", icon="EXPORT")
        if farm.last_job_id:
            layout.label(text=f"Last job: {farm.last_job_id}")


CLASSES = (PRISM_PT_farm,)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
