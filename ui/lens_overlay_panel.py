"""Lens overlay controls: a 3D viewport sidebar panel (tab "Prism") and a panel in the
camera's Object Data properties. Both show the same settings; changes redraw at once
(the settings' update callbacks tag the viewports, and the overlay recomputes its fans
the next time it draws)."""

from __future__ import annotations

import bpy

from . import lens_overlay_draw as draw


def _draw_status(layout, scene):
    if not draw.overlay_settings(scene).enabled:
        layout.label(text="Show the overlay to trace the fans and spot diagram", icon="INFO")
        return
    diagram, message = draw.scene_diagram(scene)
    if diagram is None:
        layout.label(text=message, icon="INFO")
        return
    column = layout.column(align=True)
    column.label(text=f"{diagram.name}, f/{diagram.f_number:.2g}", icon="OUTLINER_OB_CAMERA")
    for spot in diagram.spots:
        rms = "no rays reach the sensor" if not len(spot.hits_mm) else f"RMS spot {1000 * spot.rms_radius_mm:.1f} µm"
        column.label(text=f"{spot.wavelength_nm:g} nm: {rms}")


def draw_overlay_settings(layout, context, show_camera=True):
    """The overlay's settings, the status line and, with ``show_camera``, the scene camera's
    lens, focus distance and f-stop."""
    scene = context.scene
    settings = draw.overlay_settings(scene)
    if settings is None:
        layout.label(text="Prism's settings are not registered", icon="ERROR")
        return
    enabled = settings.enabled
    layout.operator(
        "prism.toggle_lens_overlay",
        text="Hide Lens Overlay" if enabled else "Show Lens Overlay",
        icon="HIDE_OFF" if enabled else "HIDE_ON",
        depress=enabled,
    )
    layout.use_property_split = True
    layout.use_property_decorate = False
    column = layout.column()
    column.prop(settings, "wavelength_source")
    if settings.wavelength_source == "CUSTOM":
        column.prop(settings, "custom_wavelengths_nm", text="Wavelengths (nm)")
        error = getattr(settings, "custom_wavelengths_error", "")
        if error:
            column.label(text=error, icon="ERROR")
    column.prop(settings, "rays_per_fan")
    column.prop(settings, "field_angle_deg")
    column.prop(settings, "source_distance_m")
    column = layout.column(heading="Show", align=True)
    column.prop(settings, "show_outlines")
    column.prop(settings, "show_sensor")
    column.prop(settings, "show_spot_diagram")
    camera = scene.camera
    if show_camera and camera is not None and camera.type == "CAMERA":
        column = layout.column()
        prism = getattr(camera.data, "prism", None)
        if prism is not None:
            column.prop(prism, "lens_model")
            if prism.lens_model == "REAL_LENS":
                column.prop(prism, "lens_source")
                column.prop(prism, "bundled_lens" if prism.lens_source == "BUNDLED" else "lens_file")
        column.prop(camera.data.dof, "focus_distance")
        column.prop(camera.data.dof, "aperture_fstop")
    _draw_status(layout.box(), scene)
    layout.operator("prism.export_lens_diagram", icon="EXPORT")


class VIEW3D_PT_prism_lens_overlay(bpy.types.Panel):
    """Lens overlay settings in the 3D viewport's sidebar."""

    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Prism"
    bl_label = "Lens Overlay"

    def draw(self, context):
        draw_overlay_settings(self.layout, context)


class PRISM_PT_camera_lens_overlay(bpy.types.Panel):
    """Lens overlay settings under the camera's Prism Lens panel (Prism engine only); the
    lens, focus and f-stop are in the parent panel and its Focus sub-panel."""

    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "data"
    bl_label = "Lens Overlay"
    bl_options = {"DEFAULT_CLOSED"}
    COMPAT_ENGINES = {"PRISM"}
    PARENT = "PRISM_PT_camera_lens"

    @classmethod
    def poll(cls, context):
        return context.camera is not None and context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        camera = context.scene.camera
        if camera is None or camera.data != context.camera:
            name = camera.name if camera is not None else "none"
            self.layout.label(text=f"The overlay follows the scene camera ({name})", icon="INFO")
        draw_overlay_settings(self.layout, context, show_camera=False)


_CLASSES = (VIEW3D_PT_prism_lens_overlay, PRISM_PT_camera_lens_overlay)


def register():
    # A sub-panel of the camera's Prism Lens panel when that is registered (it is, earlier
    # in ui/__init__.py's order); a panel of its own otherwise.
    parent = PRISM_PT_camera_lens_overlay.PARENT
    if hasattr(bpy.types, parent):
        PRISM_PT_camera_lens_overlay.bl_parent_id = parent
    elif "bl_parent_id" in PRISM_PT_camera_lens_overlay.__dict__:
        del PRISM_PT_camera_lens_overlay.bl_parent_id
    for cls in _CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
