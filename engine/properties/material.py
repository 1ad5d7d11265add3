"""``Material.prism``: what Prism adds to a material's Principled BSDF (glass, metal, coatings, films)."""

import importlib

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty

from ._common import DynamicEnumCache, register_group, stable_enum_number, unregister_group
from .spectrum_sources import (DEFAULT_PATCH, illuminant_property, line_wavelength_property, line_width_property,
                               reflectance_search, spectrum_file_property, temperature_property)

DEFAULT_GLASS = "N-BK7"

GLASS_SOURCE_ITEMS = [
    ("PRINCIPLED_IOR", "Constant IOR", "The Principled BSDF's IOR at every wavelength: no dispersion", 0),
    ("CATALOGUE", "Catalogue Glass", "A named glass from the manufacturers' catalogues (Sellmeier dispersion: "
     "a path through it keeps one wavelength, so its light is noisier in colour)", 1),
    ("ABBE", "Abbe Number", "A glass defined by its refractive index n_d and Abbe number V_d (dispersive, as "
     "Catalogue Glass)", 2),
]

CONDUCTOR_ITEMS = [
    ("FROM_COLOR", "From Base Colour", "The Principled BSDF's base colour is the reflectance at normal incidence", 0),
    ("AU", "Gold", "Measured complex refractive index of gold", 1),
    ("AG", "Silver", "Measured complex refractive index of silver", 2),
    ("CU", "Copper", "Measured complex refractive index of copper", 3),
    ("AL", "Aluminium", "Measured complex refractive index of aluminium", 4),
]

EMISSION_SOURCE_ITEMS = [
    ("COLOR", "Emission Colour", "The Principled BSDF's emission colour, turned into a smooth spectrum", 0),
    ("BLACKBODY", "Blackbody", "The spectrum of a blackbody at a colour temperature", 1),
    ("MONOCHROMATIC", "Monochromatic", "A narrow emission line at one wavelength", 2),
    ("ILLUMINANT", "Illuminant", "A measured standard illuminant (colour-science's SDS_ILLUMINANTS)", 3),
    ("FILE", "Spectrum File", "A measured emission spectrum read from a file", 4),
]

REFLECTANCE_SOURCE_ITEMS = [
    ("COLOR", "Base Colour", "The Principled BSDF's base colour, turned into a smooth reflectance spectrum", 0),
    ("MEASURED", "Measured", "A measured colour-checker patch (colour-science's SDS_COLOURCHECKERS)", 1),
    ("FILE", "Reflectance File", "A measured reflectance (values 0-1) read from a file", 2),
]

# Enum identifier → name used by ``engine.tracer.scene.Material.conductor``.
CONDUCTOR_NAMES = {"FROM_COLOR": None, "AU": "Au", "AG": "Ag", "CU": "Cu", "AL": "Al"}

_glass_cache = DynamicEnumCache("NONE", "No glass catalogue", "The glass catalogue is not available")


def glass_catalogue_names() -> list[str]:
    """Names of the catalogue glasses (empty when the catalogue is unavailable)."""
    try:
        glass = importlib.import_module("..tracer.spectra.glass", __package__)
        return sorted(str(name) for name in glass.glass_names())
    except Exception:  # noqa: BLE001 - an enum callback must never raise
        return []


def _glass_items(self, context):
    return _glass_cache.update([(name, name, f"Catalogue glass {name}") for name in glass_catalogue_names()])


class PrismMaterialSettings(bpy.types.PropertyGroup):
    """Prism settings of a material."""

    glass_source: EnumProperty(
        name="Glass",
        description="Where the refractive index of a transmissive material comes from",
        items=GLASS_SOURCE_ITEMS,
        default="PRINCIPLED_IOR",
    )
    glass_name: EnumProperty(
        name="Catalogue Glass",
        description="Glass from the manufacturers' catalogues",
        items=_glass_items,
        default=stable_enum_number(DEFAULT_GLASS, set()),
    )
    glass_nd: FloatProperty(
        name="n_d",
        description="Refractive index at the helium d line (587.6 nm)",
        default=1.5168,
        min=1.0,
        soft_max=2.5,
        max=4.0,
        precision=4,
    )
    glass_vd: FloatProperty(
        name="V_d",
        description="Abbe number (n_d - 1) / (n_F - n_C): lower means more dispersion",
        default=64.17,
        min=5.0,
        max=120.0,
        precision=2,
    )
    conductor: EnumProperty(
        name="Metal",
        description="Which metal a metallic material is",
        items=CONDUCTOR_ITEMS,
        default="FROM_COLOR",
    )
    coating_thickness_nm: FloatProperty(
        name="Coating Thickness",
        description="Thickness in nm of a thin coating over the surface (0 = no coating); "
        "coatings cause interference colours",
        default=0.0,
        min=0.0,
        soft_max=2000.0,
        max=100000.0,
    )
    coating_ior: FloatProperty(
        name="Coating IOR",
        description="Refractive index of the coating (1.38 = magnesium fluoride anti-reflection coating)",
        default=1.38,
        min=1.0,
        soft_max=3.0,
        max=5.0,
    )
    is_thin_film: BoolProperty(
        name="Thin Film",
        description="The object is a free-standing film (a soap bubble): it reflects and transmits with "
        "interference colours",
        default=False,
    )
    film_thickness_nm: FloatProperty(
        name="Film Thickness",
        description="Thickness of the free-standing film in nm",
        default=500.0,
        min=0.0,
        soft_max=2000.0,
        max=100000.0,
    )
    film_ior: FloatProperty(
        name="Film IOR",
        description="Refractive index of the free-standing film (1.33 = soapy water)",
        default=1.33,
        min=1.0,
        soft_max=3.0,
        max=5.0,
    )

    emission_source: EnumProperty(
        name="Emission Spectrum",
        description="How the spectrum of the material's emission is defined (its strength is the Principled "
        "BSDF's Emission Strength)",
        items=EMISSION_SOURCE_ITEMS,
        default="COLOR",
    )
    emission_temperature_k: temperature_property("Colour temperature of the blackbody emission in kelvin")
    emission_wavelength_nm: line_wavelength_property()
    emission_line_width_nm: line_width_property()
    emission_illuminant: illuminant_property("colour-science's key of the standard illuminant the surface emits")
    emission_file: spectrum_file_property("Spectrum File", "Measured emission spectrum of the surface")
    reflectance_source: EnumProperty(
        name="Base Colour Spectrum",
        description="Where the reflectance spectrum used as base colour (diffuse albedo, metal tint) comes from",
        items=REFLECTANCE_SOURCE_ITEMS,
        default="COLOR",
    )
    measured_reflectance: StringProperty(
        name="Measured Reflectance",
        description="A colour-checker patch as '<checker>: <patch>', e.g. 'ColorChecker N Ohta: dark skin'",
        default=DEFAULT_PATCH,
        search=reflectance_search,
        search_options=set(),
    )
    reflectance_file: spectrum_file_property("Reflectance File", "Measured reflectance (0-1) of the surface")


def register():
    register_group(PrismMaterialSettings, bpy.types.Material, "prism", "Prism material settings")


def unregister():
    unregister_group(PrismMaterialSettings, bpy.types.Material, "prism")
