"""A ``scene.Material`` described by its kind (diffuse, conductor, dielectric, thin film) as one closure:
the materials tests and benchmarks build in code, and the fallback for materials without nodes."""

from __future__ import annotations

from ..bsdf.closure import (CONDUCTOR, DIELECTRIC, DIFFUSE, FRESNEL_CONDUCTOR, FRESNEL_SCHLICK, GLASS, THIN_FILM,
                            TRANSPARENT)
from ..errors import PrismInputError
from ..scene import SpectrumSpec
from .shader import ClosureSpec, Colour, ShaderProgram


def is_emissive(material) -> bool:
    """True if the material emits light (strength > 0 and a non-black spectrum)."""
    if not material.emission_strength > 0:
        return False
    spec = material.emission
    return spec is None or spec.kind != "rgb" or max(spec.rgb) > 0


def glass_of(material):
    """The material's ``Glass``: catalogue name, n_d/V_d, n_d alone, or the constant ``ior``."""
    from ..spectra import glass

    if material.glass:
        return glass.glass_by_name(material.glass)
    if material.glass_nd is not None and material.glass_vd is not None:
        return glass.glass_from_abbe(material.glass_nd, material.glass_vd)
    if material.glass_nd is not None:
        return glass.constant_ior(material.glass_nd)
    return glass.constant_ior(material.ior)


def _alpha(material) -> float:
    r = float(material.roughness)
    if not 0.0 <= r <= 1.0:
        raise PrismInputError(f"Material '{material.name}': roughness must be within 0-1 (got {r}).")
    return r * r


def _coating(material, spec):
    if material.coating_thickness_nm > 0:
        spec.coat_nm = float(material.coating_thickness_nm)
        spec.coat_ior = float(material.coating_ior)
        if not spec.coat_ior > 0:
            raise PrismInputError(
                f"Material '{material.name}': the coating's IOR must be positive (got {material.coating_ior})."
            )
    return spec


def legacy_shader(material) -> ShaderProgram:
    """The one-closure program of a kind-described material."""
    kind = material.kind
    base = (Colour(spectrum=material.reflectance) if getattr(material, "reflectance", None) is not None
            else Colour(rgb=tuple(material.base_color)))
    if kind == "diffuse":
        closure = ClosureSpec(DIFFUSE, s0=base)
    elif kind == "conductor":
        closure = _coating(material, ClosureSpec(CONDUCTOR, alpha=_alpha(material)))
        if material.conductor:
            closure.fresnel = FRESNEL_CONDUCTOR
            closure.s0 = Colour(spectrum=("n", material.conductor))
            closure.s1 = Colour(spectrum=("k", material.conductor))
        else:
            closure.fresnel = FRESNEL_SCHLICK
            closure.s0 = base
    elif kind == "dielectric":
        closure = _coating(material, ClosureSpec(DIELECTRIC, alpha=_alpha(material), fresnel=GLASS,
                                                 glass=glass_of(material)))
    elif kind == "thin_film":
        if not (material.film_thickness_nm >= 0 and material.film_ior > 0):
            raise PrismInputError(f"Material '{material.name}': film thickness and IOR must be positive.")
        closure = ClosureSpec(THIN_FILM, film_nm=float(material.film_thickness_nm),
                              film_ior=float(material.film_ior))
    elif kind == "null":  # no surface: what Cycles renders for a material with only a volume
        closure = ClosureSpec(TRANSPARENT, tint=Colour(rgb=(1.0, 1.0, 1.0)))
    else:
        raise PrismInputError(
            f"Material '{material.name}': unknown kind '{kind}'; use diffuse, conductor, dielectric, thin_film or "
            "null."
        )
    shader = ShaderProgram([closure], surface_missing=kind == "null")
    if is_emissive(material):
        shader.emission = Colour(spectrum=material.emission or SpectrumSpec())
        shader.emission_strength = float(material.emission_strength)
    return shader
