"""Light data properties: type, spectrum (colour source), strength and shape."""

from __future__ import annotations

import bpy

from ..engine.properties.light import uses_blender_temperature
from ..engine.properties.spectrum_sources import TEMPERATURE_RANGE_K
from ._panel_base import PrismPanel, error_label
from .spectrum_display import draw_spectrum


class PRISM_PT_light(PrismPanel, bpy.types.Panel):
    """The light's type, spectrum, swatch, strength and size."""

    bl_label = "Light"
    bl_context = "data"

    @classmethod
    def poll(cls, context):
        return context.engine == "PRISM" and context.light is not None

    def draw(self, context):
        layout = self.layout
        light = context.light
        settings = light.prism
        layout.row().prop(light, "type", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False

        column = layout.column()
        column.prop(settings, "color_source")
        if settings.color_source == "RGB":
            column.prop(light, "color")
            if hasattr(light, "use_temperature"):  # Blender 4.4+: Color × a blackbody, as in Cycles
                row = column.row(heading="Temperature")
                row.prop(light, "use_temperature", text="")
                value = row.row()
                value.active = light.use_temperature
                value.prop(light, "temperature", text="")
        elif settings.color_source == "BLACKBODY":
            column.prop(settings, "temperature_k")
            low, high = TEMPERATURE_RANGE_K
            if not low <= settings.temperature_k <= high:
                error_label(column, f"Temperature must be {low:.0f}-{high:.0f} K to render.")
        elif settings.color_source == "MONOCHROMATIC":
            column.prop(settings, "wavelength_nm")
            column.prop(settings, "line_width_nm")
        elif settings.color_source == "ILLUMINANT":
            column.prop(settings, "illuminant")
        else:
            column.prop(settings, "spectrum_file")
        if settings.color_source != "RGB" or uses_blender_temperature(light):
            column.prop(settings, "preview_color", text="Resulting Colour")

        layout.separator()
        column = layout.column()
        column.prop(light, "energy", text="Strength" if light.type == "SUN" else "Power")
        if hasattr(light, "exposure"):
            column.prop(light, "exposure")
        if light.type == "AREA" and hasattr(light, "normalize"):
            column.prop(light, "normalize")
        if light.type in {"POINT", "SPOT"}:
            column.prop(light, "shadow_soft_size", text="Radius")
        elif light.type == "SUN":
            column.prop(light, "angle")
        elif light.type == "AREA":
            column.prop(light, "shape")
            sub = column.column(align=True)
            if light.shape in {"SQUARE", "DISK"}:
                sub.prop(light, "size")
            else:
                sub.prop(light, "size", text="Size X")
                sub.prop(light, "size_y", text="Y")


class PRISM_PT_light_spectrum(PrismPanel, bpy.types.Panel):
    """The light's spectrum over the visible range, its CCT and colour rendering indices."""

    bl_label = "Spectrum"
    bl_context = "data"
    bl_parent_id = "PRISM_PT_light"

    @classmethod
    def poll(cls, context):
        return context.engine == "PRISM" and context.light is not None

    def draw(self, context):
        from ..engine.export.spectra import light_emission_source
        from ..engine.output.spectrum_preview import emission_preview

        light = context.light
        preview = emission_preview(light_emission_source(light.name, light))
        draw_spectrum(self.layout, "light_spectrum", preview, "Relative spectral power, 360-830 nm", metrics=True)


class PRISM_PT_light_beam(PrismPanel, bpy.types.Panel):
    """Spot light cone."""

    bl_label = "Beam Shape"
    bl_context = "data"
    bl_parent_id = "PRISM_PT_light"

    @classmethod
    def poll(cls, context):
        return context.engine == "PRISM" and context.light is not None and context.light.type == "SPOT"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        light = context.light
        column = layout.column()
        column.prop(light, "spot_size", text="Size")
        column.prop(light, "spot_blend", text="Blend", slider=True)
        column.prop(light, "show_cone")


CLASSES = (PRISM_PT_light, PRISM_PT_light_spectrum, PRISM_PT_light_beam)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
