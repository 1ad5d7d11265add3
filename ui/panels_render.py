"""Render and View Layer properties: sampling (adaptive, time limit, denoising), light paths, wavelengths
(with their plot), performance (threads, tiles), passes."""

from __future__ import annotations

import bpy

from . import spectral_plot
from ._panel_base import PrismPanel, ToggledScenePanel

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
        heading = layout.column(align=True, heading="Noise Threshold")
        row = heading.row(align=True)
        row.prop(settings, "use_adaptive_sampling", text="")
        sub = row.row()
        sub.active = settings.use_adaptive_sampling
        sub.prop(settings, "adaptive_threshold", text="")
        sub = heading.column(align=True)
        sub.active = settings.use_adaptive_sampling
        sub.prop(settings, "adaptive_min_samples", text="Min Samples")
        column = layout.column()
        column.prop(settings, "time_limit")
        column.prop(settings, "samples_per_pass")
        column.prop(settings, "seed")
        column.prop(settings, "pixel_filter")
        sub = column.column()
        sub.active = settings.pixel_filter == "GAUSSIAN"
        sub.prop(settings, "filter_width_px")


class PRISM_PT_denoise(ToggledScenePanel, bpy.types.Panel):
    """Final-frame denoising (OpenImageDenoise, as the compositor's Denoise node)."""

    bl_label = "Denoise"
    bl_context = "render"
    bl_parent_id = "PRISM_PT_sampling"

    toggle = "use_denoising"
    settings = ("denoising_prefilter", "denoising_quality")


#: Cycles' per-kind bounce limits Prism renders where the scene sets them (``export.light_path_tricks``).
_KIND_LIMITS = ("diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces")


def _draw_kind_limits(layout, scene):
    """The per-kind limits the scene sets in Cycles' Light Paths (only those: Cycles' defaults are not applied)."""
    cycles = getattr(scene, "cycles", None)
    shown = [name for name in _KIND_LIMITS if cycles is not None and cycles.is_property_set(name)]
    if not shown:
        return
    column = layout.column(align=True, heading="Cycles' Limits")
    for name in shown:
        column.prop(cycles, name)


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
        column.prop(settings, "transparent_max_bounces", text="Transparent")
        _draw_kind_limits(layout, context.scene)
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
        settings = context.scene.prism
        layout.prop(settings, "threads")
        heading = layout.column(align=True, heading="Tiling")
        heading.prop(settings, "use_auto_tile", text="")
        sub = heading.column()
        sub.active = settings.use_auto_tile
        sub.prop(settings, "tile_size")


class PRISM_PT_spectral_output(ToggledScenePanel, bpy.types.Panel):
    """The optional multispectral EXR."""

    bl_label = "Spectral Output"
    bl_context = "render"
    bl_options = {"DEFAULT_CLOSED"}

    toggle = "use_spectral_output"
    settings = ("spectral_band_nm", "spectral_output_path")

    def draw_more(self, column) -> None:
        column.label(text="Bands as S0.<nm> channels (Fichet et al. 2021), with the render as R, G, B.")


class _PassesPanel(PrismPanel):
    bl_context = "view_layer"
    bl_parent_id = "VIEWLAYER_PT_layer_passes"


def _pass_column(layout, heading):
    layout.use_property_split = True
    layout.use_property_decorate = False
    return layout.column(heading=heading, align=True)


class PRISM_PT_passes_data(_PassesPanel, bpy.types.Panel):
    """Data passes: Blender's switches, plus Prism's denoising data, noise and sample count."""

    bl_label = "Data"

    def draw(self, context):
        layer = context.view_layer
        prism = context.scene.prism
        column = _pass_column(self.layout, "Include")
        column.prop(layer, "use_pass_combined")
        column.prop(layer, "use_pass_z")
        column.prop(layer, "use_pass_mist")
        column.prop(layer, "use_pass_position")
        column.prop(layer, "use_pass_normal")
        vector = column.column()
        vector.active = not context.scene.render.use_motion_blur  # Cycles writes no Vector pass with motion blur
        vector.prop(layer, "use_pass_vector")
        column.prop(layer, "use_pass_uv")
        column = _pass_column(self.layout, "Indexes")
        column.prop(layer, "use_pass_object_index")
        column.prop(layer, "use_pass_material_index")
        column = _pass_column(self.layout, "Other")
        column.prop(prism, "use_pass_denoising_data")
        column.prop(prism, "use_pass_variance")
        column.prop(prism, "use_pass_sample_count")
        self.layout.prop(layer, "pass_alpha_threshold")  # cut-outs below it show the surface behind them


class PRISM_PT_passes_light(_PassesPanel, bpy.types.Panel):
    """Light passes with Cycles' meanings: (Direct + Indirect) x Color of each lobe, + Emission + Environment
    add up to Combined."""

    bl_label = "Light"

    def draw(self, context):
        layer = context.view_layer
        for heading, lobe in (("Diffuse", "diffuse"), ("Glossy", "glossy"), ("Transmission", "transmission")):
            column = _pass_column(self.layout, heading)
            column.prop(layer, f"use_pass_{lobe}_direct", text="Direct")
            column.prop(layer, f"use_pass_{lobe}_indirect", text="Indirect")
            column.prop(layer, f"use_pass_{lobe}_color", text="Color")
        column = _pass_column(self.layout, "Other")
        column.prop(layer, "use_pass_emit", text="Emission")
        column.prop(layer, "use_pass_environment")
        column.prop(layer, "use_pass_ambient_occlusion", text="Ambient Occlusion")
        cycles = getattr(layer, "cycles", None)  # Cycles' own switch, which Prism reads (Cycles is a core add-on)
        if cycles is not None:
            column.prop(cycles, "use_pass_shadow_catcher")


CLASSES = (PRISM_PT_sampling, PRISM_PT_denoise, PRISM_PT_light_paths, PRISM_PT_wavelengths, PRISM_PT_spectral_output,
           PRISM_PT_performance, PRISM_PT_passes_data, PRISM_PT_passes_light)


register, unregister = bpy.utils.register_classes_factory(CLASSES)
