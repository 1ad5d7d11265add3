"""What ``Material.prism`` adds to the closures a node tree makes: a dispersive glass (catalogue or n_d/V_d)
for every refracting closure, a measured metal for metallic ones, a thin-film coating over both."""

from __future__ import annotations

from ...properties.material import CONDUCTOR_ITEMS, CONDUCTOR_NAMES
from ...tracer.bsdf.closure import FRESNEL_CONDUCTOR
from ...tracer.errors import PrismInputError

_METAL_LABELS = {identifier: label for identifier, label, *_ in CONDUCTOR_ITEMS}


def glass_override(c, closure) -> None:
    """Give a dielectric closure the material's catalogue or Abbe glass (its IOR input then does nothing)."""
    from ...tracer.spectra import glass as glass_catalogue

    settings = c.settings
    name = c.material.name
    if settings is None or settings.glass_source == "PRINCIPLED_IOR":
        return
    if settings.glass_source == "CATALOGUE":
        glass_name = settings.glass_name
        if not glass_name or glass_name == "NONE":
            raise PrismInputError(
                f"Material '{name}' uses a catalogue glass that is not in Prism's catalogue "
                f"(stored value {settings.get('glass_name', '?')}): choose a glass in Material ▸ Prism ▸ Glass."
            )
        try:
            closure.glass = glass_catalogue.glass_by_name(glass_name)
        except PrismInputError as error:
            raise PrismInputError(f"Material '{name}': {error}") from None
        c.glass_description = ("catalogue", glass_name)
    elif settings.glass_source == "ABBE":
        try:
            closure.glass = glass_catalogue.glass_from_abbe(settings.glass_nd, settings.glass_vd)
        except PrismInputError as error:
            raise PrismInputError(f"Material '{name}': {error}") from None
        c.glass_description = ("abbe", (float(settings.glass_nd), float(settings.glass_vd)))


def conductor_override(c, closure) -> None:
    """Give a metallic closure the material's measured metal (complex index n + ik)."""
    settings = c.settings
    metal = CONDUCTOR_NAMES.get(settings.conductor) if settings is not None else None
    if metal:
        closure.fresnel = FRESNEL_CONDUCTOR
        closure.s0 = ("n", metal)
        closure.s1 = ("k", metal)
        c.conductor = metal
        if closure.measured is not None:  # the metal's n and k give its reflectance: s0 must stay n
            closure.measured = None
            label = _METAL_LABELS[settings.conductor]
            c.warn(closure.node, f"is a measured metal ({label}, Material ▸ Prism ▸ Metal), whose n and k give its "
                                 "reflectance; the measured base colour of Material ▸ Prism ▸ Base Colour Spectrum "
                                 "is not used on it.")


def prism_coating(c, closure) -> None:
    """Put the material's thin-film coating (Material ▸ Prism ▸ Coating) over a glass or metal closure."""
    settings = c.settings
    if settings is None or not settings.coating_thickness_nm > 0:
        return
    thickness, index = float(settings.coating_thickness_nm), float(settings.coating_ior)
    check_film(c.material.name, "Material ▸ Prism ▸ Coating Thickness", thickness, "Material ▸ Prism ▸ Coating IOR",
               index)
    closure.coat_nm, closure.coat_ior = thickness, index


def check_film(name: str, thickness_setting: str, thickness_nm: float, index_setting: str, index: float) -> None:
    """A thin film or coating needs a finite thickness and an index of 1 or more (1.33 soapy water, 1.38 MgF2)."""
    import math

    if not (math.isfinite(thickness_nm) and thickness_nm >= 0):
        raise PrismInputError(f"Material '{name}': {thickness_setting} is {thickness_nm:g} nm; use 0 nm or more.")
    if not (math.isfinite(index) and index >= 1.0):
        raise PrismInputError(
            f"Material '{name}': {index_setting} is {index:g}; a film's refractive index must be 1 or more "
            "(1.33 for soapy water, 1.38 for a magnesium fluoride coating)."
        )
