"""Blender materials → ``tracer.scene.Material``: the Principled BSDF plus ``Material.prism``.

What is read lives in ``engine.properties.principled`` (shared with the material
panel, so the panel shows what renders); this module turns it into a tracer
material and validates the glass. Inputs Prism does not model become warnings,
one per material and socket.
"""

from __future__ import annotations

import math

from ..properties.material import CONDUCTOR_NAMES
from ..properties.principled import material_kind, read_principled, surface_node
from ..tracer.errors import PrismInputError
from ..tracer.scene import Material, SpectrumSpec
from .aovs import read_aovs
from .spectra import material_emission_source, material_reflectance_source

DEFAULT_MATERIAL = Material(name="Default", kind="diffuse", base_color=(0.8, 0.8, 0.8))


def _glass(material, settings, exported: Material) -> None:
    from ..tracer.spectra import glass as glass_catalogue

    name = material.name
    if settings.glass_source == "CATALOGUE":
        glass_name = settings.glass_name
        if not glass_name or glass_name == "NONE":
            raise PrismInputError(
                f"Material '{name}' uses a catalogue glass that is not in Prism's catalogue "
                f"(stored value {settings.get('glass_name', '?')}): choose a glass in Material ▸ Prism ▸ Glass."
            )
        try:
            glass_catalogue.glass_by_name(glass_name)
        except PrismInputError as error:
            raise PrismInputError(f"Material '{name}': {error}") from None
        exported.glass = glass_name
    elif settings.glass_source == "ABBE":
        try:
            glass_catalogue.glass_from_abbe(settings.glass_nd, settings.glass_vd)
        except PrismInputError as error:
            raise PrismInputError(f"Material '{name}': {error}") from None
        exported.glass_nd = float(settings.glass_nd)
        exported.glass_vd = float(settings.glass_vd)


def export_material(material, warnings: list[str] | None = None) -> Material:
    """The tracer material for a Blender material (None → the default grey diffuse)."""
    if material is None:
        return DEFAULT_MATERIAL
    # The original data-block: what the user (or a script) set last, even when the depsgraph
    # has not re-copied it (Python edits to settings do not tag the material for evaluation).
    material = material.original
    node = surface_node(material) if material.use_nodes else None
    if node is not None and node.bl_idname == "ShaderNodeHoldout":
        return Material(name=material.name, kind="diffuse", base_color=(0.0, 0.0, 0.0), holdout=True)
    reading = read_principled(material)
    if warnings is not None:
        warnings.extend(reading.ignored)
    settings = getattr(material, "prism", None)
    kind = material_kind(reading, settings)
    name = material.name
    values = {
        "base_color": reading.base_color,
        "roughness": reading.roughness,
        "ior": reading.ior,
        "emission_strength": reading.emission_strength,
    }
    for label, value in (("Roughness", reading.roughness), ("IOR", reading.ior), ("Emission Strength", reading.emission_strength)):
        if not math.isfinite(value):
            raise PrismInputError(f"Material '{name}': {label} is {value}; enter a finite number.")
    if not all(math.isfinite(c) and c >= 0 for c in reading.base_color + reading.emission_color):
        raise PrismInputError(f"Material '{name}': a colour is negative, NaN or infinite; pick a colour again.")
    if kind == "dielectric" and reading.ior < 1.0 and (settings is None or settings.glass_source == "PRINCIPLED_IOR"):
        raise PrismInputError(
            f"Material '{name}': IOR {reading.ior:g} is below 1; Prism's glass needs an IOR of 1 or more."
        )
    exported = Material(name=name, kind=kind, **values)
    exported.aovs = read_aovs(material, warnings)
    if reading.emission_strength < 0:
        raise PrismInputError(f"Material '{name}': Emission Strength {reading.emission_strength:g} is negative.")
    spectral = settings is not None and settings.emission_source != "COLOR"
    if reading.emission_strength > 0 and (spectral or max(reading.emission_color) > 0):
        exported.emission = (material_emission_source(material, reading.emission_color).spec() if spectral
                             else SpectrumSpec(kind="rgb", rgb=reading.emission_color))
    else:
        exported.emission_strength = 0.0
    if settings is None:
        return exported
    exported.reflectance = material_reflectance_source(material, reading.base_color).spec()
    if exported.reflectance is not None and kind in {"dielectric", "thin_film"} and warnings is not None:
        warnings.append(f"Material '{name}': a measured base colour only acts on diffuse and metal surfaces; "
                        f"it is ignored on {'glass' if kind == 'dielectric' else 'a thin film'}.")
    if kind == "dielectric":
        _glass(material, settings, exported)
    elif kind == "conductor":
        exported.conductor = CONDUCTOR_NAMES[settings.conductor]
    elif kind == "thin_film":
        exported.film_thickness_nm = float(settings.film_thickness_nm)
        exported.film_ior = float(settings.film_ior)
    if kind == "thin_film":
        _check_film(name, "Material ▸ Prism ▸ Film Thickness", exported.film_thickness_nm,
                    "Material ▸ Prism ▸ Film IOR", exported.film_ior)
    if settings.coating_thickness_nm > 0:
        exported.coating_thickness_nm = float(settings.coating_thickness_nm)
        exported.coating_ior = float(settings.coating_ior)
        where = "Material ▸ Prism ▸ Coating"
    elif reading.thin_film_thickness_nm > 0:
        # Blender 4.2+'s Principled thin film is a coating on the surface.
        exported.coating_thickness_nm = reading.thin_film_thickness_nm
        exported.coating_ior = reading.thin_film_ior
        where = "Principled BSDF ▸ Thin Film"
    if exported.coating_thickness_nm > 0 and kind in {"diffuse", "thin_film"} and warnings is not None:
        warnings.append(f"Material '{name}': a coating only acts on glass or metal; it is ignored on a {kind.replace('_', ' ')} surface.")
    elif exported.coating_thickness_nm > 0:
        _check_film(name, f"{where} Thickness", exported.coating_thickness_nm, f"{where} IOR", exported.coating_ior)
    return exported


def _check_film(name: str, thickness_setting: str, thickness_nm: float, index_setting: str, index: float) -> None:
    """A thin film or coating needs a finite thickness and an index of 1 or more (1.33 soapy water, 1.38 MgF2)."""
    if not (math.isfinite(thickness_nm) and thickness_nm >= 0):
        raise PrismInputError(f"Material '{name}': {thickness_setting} is {thickness_nm:g} nm; use 0 nm or more.")
    if not (math.isfinite(index) and index >= 1.0):
        raise PrismInputError(
            f"Material '{name}': {index_setting} is {index:g}; a film's refractive index must be 1 or more "
            "(1.33 for soapy water, 1.38 for a magnesium fluoride coating)."
        )
