"""``Light.prism``: how a light's spectrum is defined. Strength is Blender's own light energy."""

import bpy
from bpy.props import EnumProperty, FloatVectorProperty

from ._common import register_group, unregister_group
from .spectral_colour import blackbody_display_rgb, line_display_rgb
from .spectrum_sources import (TEMPERATURE_RANGE_K, illuminant_property, line_wavelength_property,  # noqa: F401
                               line_width_property, spectrum_file_property, temperature_property)
# (TEMPERATURE_RANGE_K stays importable from here, where it used to live.)

COLOR_SOURCE_ITEMS = [
    ("RGB", "RGB", "The light's colour, turned into a smooth spectrum", 0),
    ("BLACKBODY", "Blackbody", "The spectrum of a blackbody at a colour temperature", 1),
    ("MONOCHROMATIC", "Monochromatic", "A narrow emission line at one wavelength (e.g. a laser or sodium lamp)", 2),
    ("ILLUMINANT", "Illuminant", "A measured standard illuminant: CIE A and D, fluorescent FL1-FL12, high-pressure "
     "lamps HP1-HP5, LEDs (colour-science's SDS_ILLUMINANTS)", 3),
    ("FILE", "Spectrum File", "A measured spectrum read from a file (CSV, IES TM-27-14, Sekonic, UPRTek)", 4),
]


def uses_blender_temperature(light) -> bool:
    """Colour Source RGB with Blender 4.4+'s own Temperature on: the light is its Color × a blackbody."""
    return light.prism.color_source == "RGB" and bool(getattr(light, "use_temperature", False))


def _preview_color(self):
    if self.color_source == "BLACKBODY":
        return blackbody_display_rgb(self.temperature_k)
    if self.color_source == "MONOCHROMATIC":
        return line_display_rgb(self.wavelength_nm, self.line_width_nm)
    if self.color_source in ("ILLUMINANT", "FILE") or uses_blender_temperature(self.id_data):
        from ..export.spectra import light_emission_source
        from ..output.spectrum_preview import emission_preview

        preview = emission_preview(light_emission_source(self.id_data.name, self.id_data))
        return preview.display_rgb if preview is not None and preview.error is None else (0.0, 0.0, 0.0)
    return tuple(self.id_data.color)


class PrismLightSettings(bpy.types.PropertyGroup):
    """Prism settings of a light."""

    color_source: EnumProperty(
        name="Colour Source",
        description="How the light's spectrum is defined",
        items=COLOR_SOURCE_ITEMS,
        default="RGB",
    )
    temperature_k: temperature_property("Colour temperature of the blackbody in kelvin")
    wavelength_nm: line_wavelength_property()
    line_width_nm: line_width_property()
    illuminant: illuminant_property("colour-science's key of the standard illuminant (e.g. D65, FL2, HP1, LED-B3)")
    spectrum_file: spectrum_file_property("Spectrum File", "Measured emission spectrum of the light")
    preview_color: FloatVectorProperty(
        name="Colour",
        description="Colour of the light's spectrum on screen (brightest channel 1; read-only)",
        size=3,
        subtype="COLOR",
        get=_preview_color,
    )


def register():
    register_group(PrismLightSettings, bpy.types.Light, "prism", "Prism light settings")


def unregister():
    unregister_group(PrismLightSettings, bpy.types.Light, "prism")
