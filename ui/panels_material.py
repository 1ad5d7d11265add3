"""Material properties: what Prism reads from the Principled BSDF, and Prism's overrides."""

from __future__ import annotations

from collections import namedtuple

import bpy

from ..engine.properties.principled import read_principled
from ._panel_base import PrismPanel, error_label
from .spectrum_display import draw_spectrum

_evaluator = []  # the constant folder, once kernels are on disk

#: What a render makes of a material: lobe names, whether it emits, warnings, and the names of the nodes whose
#: colour Material ▸ Prism's measured reflectance replaces.
Preview = namedtuple("Preview", "names emits warnings measured_nodes")


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


def _fold():
    """The kernels' constant folder if they are compiled already, else None: a panel must never wait for
    numba (the summary then also lists lobes that constant weights of 0 would remove)."""
    from ..engine.warmup import kernel_cache
    from ..engine.tracer import jit

    kernel_cache.configure()  # before any kernel is imported: the cache a render would use
    if not _evaluator and jit.cache_is_warm():
        from ..engine.tracer.materials.folding import fold_evaluator

        _evaluator.append(fold_evaluator())
    return _evaluator[0] if _evaluator else None


def _reflectance_override(material) -> dict:
    """Material ▸ Prism's measured reflectance as the compiler takes it, unread (no file, no colour-science):
    the summary needs to know only which nodes it replaces."""
    from ..engine.tracer.scene import ReflectanceSpec

    settings = material.prism
    if settings.reflectance_source == "COLOR":
        return {}
    kind = "measured" if settings.reflectance_source == "MEASURED" else "tabulated"
    return {"reflectance": ReflectanceSpec(kind=kind, name=settings.measured_reflectance)}


def _preview(material) -> Preview:
    """The material compiled as a render would (no image read)."""
    from ..engine.export.nodes import compile_material
    from ..engine.tracer.bsdf.closure import (CONDUCTOR, DIELECTRIC, DIFFUSE, FRESNEL_DIELECTRIC, FRESNEL_NONE,
                                              GLASS, SHEEN, TRANSLUCENT, TRANSPARENT)

    try:
        compiled = compile_material(material, evaluate=_fold(), load_pixels=False,
                                    overrides=_reflectance_override(material))
    except Exception as error:  # noqa: BLE001 - a panel must draw; the render reports the error itself
        return Preview([], False, [str(error)], [])
    shader = compiled.shader
    names = []
    for spec in shader.closures if shader is not None else []:
        if spec.kind == DIFFUSE:
            name = "Diffuse"
        elif spec.kind == TRANSLUCENT:
            name = "Translucent"
        elif spec.kind == TRANSPARENT:
            name = "Transparent"
        elif spec.kind == SHEEN:
            name = "Sheen"
        elif spec.kind == DIELECTRIC:
            name = "Glass (refractive)" if spec.fresnel == GLASS else "Refraction"
        elif spec.kind == CONDUCTOR:
            name = {FRESNEL_DIELECTRIC: "Specular", FRESNEL_NONE: "Glossy"}.get(spec.fresnel, "Metal")
        else:
            name = "Thin film"
        if name not in names:
            names.append(name)
    emits = shader is not None and shader.emission is not None and shader.emission_strength > 0
    return Preview(names, emits, compiled.warnings, compiled.measured_nodes)


def _kinds(material) -> Preview:
    """What ``material`` renders as with Prism."""
    if material.prism.is_thin_film:
        return Preview(["Thin film"], False, [], [])
    if not material.use_nodes or material.node_tree is None:
        return Preview(["Metal" if material.metallic >= 0.5 else "Diffuse"], False, [], ["viewport display colour"])
    return _preview(material)


class PRISM_PT_material(PrismPanel, bpy.types.Panel):
    """What Prism renders of this material's nodes, and what it leaves out."""

    bl_label = "Prism"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return _material_poll(context)

    def draw(self, context):
        layout = self.layout
        material = context.material
        names, emits, warnings, _ = _kinds(material)
        text = " + ".join(names) if names else "Black (nothing connected)"
        layout.label(text=f"Renders as: {text}{' + emission' if emits else ''}", icon="SHADING_RENDERED")
        layout = _split(layout)
        if not material.use_nodes or material.node_tree is None:
            column = layout.column(align=True)
            column.label(text="No nodes: using the viewport display values.", icon="INFO")
            column.prop(material, "diffuse_color", text="Base Color")
            column.prop(material, "metallic")
            column.prop(material, "roughness")
        for message in warnings:
            error_label(layout, message)


class PRISM_PT_material_glass(MaterialSubpanel, bpy.types.Panel):
    """Dispersion of a transmissive material."""

    bl_label = "Glass"

    def draw(self, context):
        layout = _split(self.layout)
        material = context.material
        settings = material.prism
        names = _kinds(material)[0]
        layout.active = "Glass (refractive)" in names or "Refraction" in names
        layout.prop(settings, "glass_source")
        if settings.glass_source == "CATALOGUE":
            layout.prop(settings, "glass_name")
        elif settings.glass_source == "ABBE":
            column = layout.column(align=True)
            column.prop(settings, "glass_nd")
            column.prop(settings, "glass_vd")
        else:
            layout.label(text="The shader's constant IOR at every wavelength: no dispersion.")


class PRISM_PT_material_metal(MaterialSubpanel, bpy.types.Panel):
    """Which metal a metallic material is."""

    bl_label = "Metal"

    def draw(self, context):
        layout = _split(self.layout)
        material = context.material
        layout.active = "Metal" in _kinds(material)[0]
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
        from ..engine.output.spectrum_preview import reflectance_preview

        layout = _split(self.layout)
        material = context.material
        settings = material.prism
        reading = read_principled(material)
        preview = _kinds(material)
        if settings.reflectance_source == "COLOR":
            layout.active = bool({"Diffuse", "Metal"} & set(preview.names))
        else:
            layout.active = bool(preview.measured_nodes)
        layout.prop(settings, "reflectance_source")
        if settings.reflectance_source == "MEASURED":
            layout.prop(settings, "measured_reflectance")
        elif settings.reflectance_source == "FILE":
            layout.prop(settings, "reflectance_file")
        if settings.reflectance_source != "COLOR":
            _draw_replaced_colours(layout, material, preview.measured_nodes)
        preview = reflectance_preview(material_reflectance_source(material, reading.base_color))
        draw_spectrum(layout, "material_reflectance", preview, "Reflectance 0-1, 360-830 nm", metrics=False)


def _draw_replaced_colours(layout, material, measured_nodes) -> None:
    """Which colours the measured reflectance replaces, or, when none, that the render keeps the nodes' own."""
    if material.prism.is_thin_film:
        error_label(layout, "A free-standing thin film has no base colour: not used.")
    elif measured_nodes:
        layout.label(text=f"Replaces the colour of: {', '.join(measured_nodes)}", icon="INFO")
    else:
        error_label(layout, "No node here has a base colour it replaces (Principled, Diffuse, Subsurface, "
                            "Metallic F82): the nodes' own colours render.")


class PRISM_PT_material_emission_spectrum(MaterialSubpanel, bpy.types.Panel):
    """The emission's spectrum (strength: the Principled BSDF's Emission Strength), its plot and metrics."""

    bl_label = "Emission Spectrum"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        from ..engine.export.spectra import material_emission_source
        from ..engine.output.spectrum_preview import emission_preview

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


class PRISM_PT_material_settings(MaterialSubpanel, bpy.types.Panel):
    """The material settings Prism reads as Cycles does (Cycles shows them in Material ▸ Settings)."""

    bl_label = "Settings"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = _split(self.layout)
        material = context.material
        layout.prop(material, "displacement_method", text="Displacement")
        cycles = getattr(material, "cycles", None)  # Cycles' own material settings
        if cycles is not None and hasattr(cycles, "use_bump_map_correction"):
            layout.prop(cycles, "use_bump_map_correction")
        if cycles is not None and hasattr(cycles, "volume_step_rate"):
            # A Density driven by nodes is baked at voxels of Cycles' step over this rate (``baked_density``).
            layout.prop(cycles, "volume_step_rate", text="Volume Step Rate")


CLASSES = (PRISM_PT_material, PRISM_PT_material_base_spectrum, PRISM_PT_material_emission_spectrum,
           PRISM_PT_material_glass, PRISM_PT_material_metal, PRISM_PT_material_films, PRISM_PT_material_settings)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
