"""Material properties: what Prism reads from the Principled BSDF, and Prism's overrides."""

from __future__ import annotations

import bpy

from ..engine.properties.principled import READ_SOCKETS, find_principled, material_kind, read_principled
from ._panel_base import PrismPanel, error_label
from .spectrum_display import draw_spectrum

_KIND_LABELS = {
    "diffuse": "Diffuse",
    "conductor": "Metal",
    "dielectric": "Glass (refractive)",
    "thin_film": "Thin film",
}


def _material_poll(context):
    return context.engine == "PRISM" and context.material is not None


class MaterialSubpanel(PrismPanel):
    """Mixin: a subpanel of Material ▸ Prism."""

    bl_context = "material"
    bl_parent_id = "PRISM_PT_material"

    @classmethod
    def poll(cls, context):
        return _material_poll(context)


def _split(layout):
    """``layout`` with properties split into label and value columns, without decorators."""
    layout.use_property_split = True
    layout.use_property_decorate = False
    return layout


class PRISM_PT_material(PrismPanel, bpy.types.Panel):
    """What Prism renders for this material."""

    bl_label = "Prism"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return _material_poll(context)

    def draw(self, context):
        layout = self.layout
        material = context.material
        reading = read_principled(material)
        kind = material_kind(reading, material.prism)
        emits = reading.emission_strength > 0.0 and (
            material.prism.emission_source != "COLOR" or max(reading.emission_color) > 0.0)
        layout.label(
            text=f"Renders as: {_KIND_LABELS[kind]}{' + emission' if emits else ''}",
            icon="SHADING_RENDERED",
        )
        layout.use_property_split = True
        layout.use_property_decorate = False
        node = find_principled(material)
        column = layout.column(align=True)
        if node is None:
            column.label(text="No Principled BSDF: using the viewport display values.", icon="INFO")
            column.prop(material, "diffuse_color", text="Base Color")
            column.prop(material, "metallic")
            column.prop(material, "roughness")
        else:
            for name in READ_SOCKETS:
                socket = node.inputs.get(name)
                if socket is None:
                    continue
                if socket.is_linked:
                    column.label(text=f"{name}: linked (ignored)", icon="ERROR")
                else:
                    column.prop(socket, "default_value", text=name)
        for message in reading.ignored:
            error_label(layout, message)


class PRISM_PT_material_glass(MaterialSubpanel, bpy.types.Panel):
    """Dispersion of a transmissive material."""

    bl_label = "Glass"

    def draw(self, context):
        layout = _split(self.layout)
        material = context.material
        settings = material.prism
        reading = read_principled(material)
        layout.active = material_kind(reading, settings) == "dielectric"
        layout.prop(settings, "glass_source")
        if settings.glass_source == "CATALOGUE":
            layout.prop(settings, "glass_name")
        elif settings.glass_source == "ABBE":
            column = layout.column(align=True)
            column.prop(settings, "glass_nd")
            column.prop(settings, "glass_vd")
        else:
            layout.label(text=f"Constant IOR {reading.ior:.4g} from the Principled BSDF: no dispersion.")


class PRISM_PT_material_metal(MaterialSubpanel, bpy.types.Panel):
    """Which metal a metallic material is."""

    bl_label = "Metal"

    def draw(self, context):
        layout = _split(self.layout)
        material = context.material
        layout.active = material_kind(read_principled(material), material.prism) == "conductor"
        layout.prop(material.prism, "conductor")


class PRISM_PT_material_films(MaterialSubpanel, bpy.types.Panel):
    """Coatings and free-standing thin films (interference colours)."""

    bl_label = "Coating and Thin Film"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = _split(self.layout)
        settings = context.material.prism
        column = layout.column(align=True)
        column.prop(settings, "coating_thickness_nm")
        sub = column.column(align=True)
        sub.active = settings.coating_thickness_nm > 0.0
        sub.prop(settings, "coating_ior")
        layout.prop(settings, "is_thin_film")
        column = layout.column(align=True)
        column.active = settings.is_thin_film
        column.prop(settings, "film_thickness_nm")
        column.prop(settings, "film_ior")


class PRISM_PT_material_base_spectrum(MaterialSubpanel, bpy.types.Panel):
    """Where the base colour's reflectance spectrum comes from, and its plot."""

    bl_label = "Base Colour Spectrum"

    def draw(self, context):
        from ..engine.export.spectra import material_reflectance_source
        from ..engine.spectrum_preview import reflectance_preview

        layout = _split(self.layout)
        material = context.material
        settings = material.prism
        reading = read_principled(material)
        layout.active = material_kind(reading, settings) in {"diffuse", "conductor"}
        layout.prop(settings, "reflectance_source")
        if settings.reflectance_source == "MEASURED":
            layout.prop(settings, "measured_reflectance")
        elif settings.reflectance_source == "FILE":
            layout.prop(settings, "reflectance_file")
        preview = reflectance_preview(material_reflectance_source(material, reading.base_color))
        draw_spectrum(layout, "material_reflectance", preview, "Reflectance 0-1, 360-830 nm", metrics=False)


class PRISM_PT_material_emission_spectrum(MaterialSubpanel, bpy.types.Panel):
    """The emission's spectrum (strength: the Principled BSDF's Emission Strength), its plot and metrics."""

    bl_label = "Emission Spectrum"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        from ..engine.export.spectra import material_emission_source
        from ..engine.spectrum_preview import emission_preview

        layout = _split(self.layout)
        material = context.material
        settings = material.prism
        reading = read_principled(material)
        layout.active = reading.emission_strength > 0.0
        layout.prop(settings, "emission_source")
        column = layout.column(align=True)
        source = settings.emission_source
        if source == "BLACKBODY":
            column.prop(settings, "emission_temperature_k")
        elif source == "MONOCHROMATIC":
            column.prop(settings, "emission_wavelength_nm")
            column.prop(settings, "emission_line_width_nm")
        elif source == "ILLUMINANT":
            column.prop(settings, "emission_illuminant")
        elif source == "FILE":
            column.prop(settings, "emission_file")
        if reading.emission_strength <= 0.0:
            layout.label(text="Set the Principled BSDF's Emission Strength above 0 to emit.", icon="INFO")
            return
        preview = emission_preview(material_emission_source(material, reading.emission_color))
        draw_spectrum(layout, "material_emission", preview, "Relative spectral power, 360-830 nm", metrics=True)


CLASSES = (PRISM_PT_material, PRISM_PT_material_base_spectrum, PRISM_PT_material_emission_spectrum,
           PRISM_PT_material_glass, PRISM_PT_material_metal, PRISM_PT_material_films)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
