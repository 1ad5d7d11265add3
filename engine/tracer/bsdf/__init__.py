"""Surface scattering models, built per ``scene.Material``.

``make_bsdf(material)`` returns one of ``Diffuse``, ``Conductor`` (mirror or rough
GGX), ``Dielectric`` (smooth or rough glass, dispersive or not) or ``ThinFilm``
(free-standing film); a coating (``coating_thickness_nm`` > 0) replaces the
interface reflectance of a conductor or dielectric by thin-film interference.
Reflectances are spectra (RGB upsampled), never RGB triples. Emission (any kind
may also emit) lives in ``emission.py`` and is sampled as a light (``lights.mesh``).
"""

from __future__ import annotations

import numpy as np

from ..errors import PrismInputError
from .base import BSDF, BSDFSample
from .conductor import Conductor
from .dielectric import Dielectric
from .diffuse import Diffuse
from .emission import emission_spectrum_of, is_emissive
from .thin_film import ThinFilm

__all__ = ["BSDF", "BSDFSample", "Conductor", "Dielectric", "Diffuse", "ThinFilm", "make_bsdf", "is_emissive",
           "emission_spectrum_of"]


def _alpha(material) -> float:
    r = float(material.roughness)
    if not 0.0 <= r <= 1.0:
        raise PrismInputError(f"Material '{material.name}': roughness must be within 0-1 (got {r}).")
    return r * r


def _schlick(f0):
    def fresnel(cos_i, lam):
        c = (1.0 - np.clip(cos_i, 0.0, 1.0))[:, None]
        r0 = f0(lam)
        return r0 + (1.0 - r0) * c**5

    return fresnel


def _measured(name):
    from .optics import conductor_fresnel

    def fresnel(cos_i, lam):
        return conductor_fresnel(cos_i, name, lam)

    return fresnel


def make_bsdf(material, spectra) -> BSDF:
    """The BSDF of a material; ``spectra`` is the ``engine.tracer.path_spectra`` module."""
    kind = material.kind
    if kind == "diffuse":
        return Diffuse(spectra.reflectance(material.base_color))
    if kind == "conductor":
        if material.coating_thickness_nm > 0:
            from .optics import coated_conductor_fresnel

            fresnel = coated_conductor_fresnel(material, spectra)
        elif material.conductor:
            fresnel = _measured(material.conductor)
        else:
            fresnel = _schlick(spectra.reflectance(material.base_color))
        return Conductor(_alpha(material), fresnel)
    if kind == "dielectric":
        coating = None
        if material.coating_thickness_nm > 0:
            from .optics import coating_reflectance

            coating = coating_reflectance(material.coating_thickness_nm, material.coating_ior)
        return Dielectric(spectra.glass_of(material), _alpha(material), coating)
    if kind == "thin_film":
        from .optics import free_film_reflectance

        if not material.film_thickness_nm >= 0 or not material.film_ior > 0:
            raise PrismInputError(f"Material '{material.name}': film thickness and IOR must be positive.")
        return ThinFilm(free_film_reflectance(material.film_thickness_nm, material.film_ior))
    raise PrismInputError(
        f"Material '{material.name}': unknown kind '{kind}'; use diffuse, conductor, dielectric or thin_film."
    )
