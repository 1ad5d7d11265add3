"""Render and View Layer properties: sampling, light paths, wavelengths (with their plot), passes."""

from __future__ import annotations

import bpy

from . import spectral_plot
from ._panel_base import PrismPanel

_PLOT_SCALE = 10.0


class PRISM_PT_sampling(PrismPanel, bpy.types.Panel):
    """Samples and seed."""

    bl_label = "Sampling"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.prism
        column = layout.column(align=True)
        column.prop(settings, "samples", text="Render")
        column.prop(settings, "preview_samples", text="Viewport")
        column = layout.column()
        column.prop(settings, "samples_per_pass")
        column.prop(settings, "seed")
        column.prop(settings, "pixel_filter")
        sub = column.column()
        sub.active = settings.pixel_filter == "GAUSSIAN"
        sub.prop(settings, "filter_width_px")


class PRISM_PT_light_paths(PrismPanel, bpy.types.Panel):
    """Bounces, Russian roulette, MIS, caustics by light tracing."""

    bl_label = "Light Paths"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.prism
        column = layout.column(align=True)
        column.prop(settings, "max_bounces", text="Max Bounces")
        column.prop(settings, "preview_max_bounces", text="Viewport")
        column = layout.column()
        column.prop(settings, "russian_roulette_depth")
        column.prop(settings, "use_mis")
        column = layout.column(heading="Caustics")
        column.prop(settings, "light_tracing")


class PRISM_PT_wavelengths(PrismPanel, bpy.types.Panel):
    """Wavelength mode, hero wavelengths, the channel Gaussians and their plot."""

    bl_label = "Wavelengths"
    bl_context = "render"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.prism
        layout.row().prop(settings, "wavelength_mode", expand=True)
        layout.use_property_split = True
        layout.use_property_decorate = False
        row = layout.row()
        row.active = settings.wavelength_mode == "CIE"
        row.prop(settings, "wavelengths_per_path")

        gaussian = settings.wavelength_mode == "GAUSSIAN_RGB"
        column = layout.column(align=True)
        column.active = gaussian
        for channel in "rgb":
            row = column.row(align=True)
            row.prop(settings, f"mean_{channel}_nm", text=f"{channel.upper()} Mean, Sigma")
            row.prop(settings, f"sigma_{channel}_nm", text="")
        if not gaussian:
            layout.label(text="The Gaussians are used in Gaussian RGB mode and by the lens overlay.", icon="INFO")

        icon = spectral_plot.plot_icon_id(settings)
        box = layout.box()
        box.template_icon(icon_value=icon, scale=_PLOT_SCALE)
        box.label(text="R, G, B Gaussians over CIE x̄ ȳ z̄, 360-830 nm")


class PRISM_PT_performance(PrismPanel, bpy.types.Panel):
    """Threads."""

    bl_label = "Performance"
    bl_context = "render"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(context.scene.prism, "threads")


class PRISM_PT_spectral_output(PrismPanel, bpy.types.Panel):
    """The optional multispectral EXR."""

    bl_label = "Spectral Output"
    bl_context = "render"
    bl_options = {"DEFAULT_CLOSED"}

    def draw_header(self, context):
        self.layout.prop(context.scene.prism, "use_spectral_output", text="")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.prism
        column = layout.column()
        column.active = settings.use_spectral_output
        column.prop(settings, "spectral_band_nm")
        column.prop(settings, "spectral_output_path")
        column.label(text="Bands as S0.<nm> channels (Fichet et al. 2021), with the render as R, G, B.")


class PRISM_PT_passes(PrismPanel, bpy.types.Panel):
    """Optional render passes (View Layer properties)."""

    bl_label = "Prism Passes"
    bl_context = "view_layer"

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        column = layout.column(heading="Include", align=True)
        column.prop(context.scene.prism, "use_pass_variance")
        column.prop(context.scene.prism, "use_pass_sample_count")


CLASSES = (PRISM_PT_sampling, PRISM_PT_light_paths, PRISM_PT_wavelengths, PRISM_PT_spectral_output, PRISM_PT_performance,
           PRISM_PT_passes)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
