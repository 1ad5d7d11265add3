"""``scene.Material`` list → ``MaterialArrays``: closure rows, glass rows, emission, capability flags.

Each material is ``closure_count`` consecutive rows of ``closures`` (see ``bsdf.closure``) starting at
``closure_start``, plus an emission (spectrum id and strength; strength 0 = not emissive) and flags
that let the kernels decide without looking at kinds:

- ``MAT_DELTA``: every closure is a delta lobe, so no light sampling at its vertices;
- ``MAT_DISPERSIVE``: a closure refracts at a wavelength-dependent index (paths keep only their hero);
- ``MAT_NULL``: a free-standing film, which shadow rays pass through (attenuated) and which paths cross
  as a null event for MIS;
- ``MAT_ONE_SIDED``: the shading frame is not flipped to face the ray (glass: inside and outside differ);
- ``MAT_EMISSIVE``: the surface emits (and is light-sampled as part of the emissive meshes).

Texture lookups and node-built layered materials (issue 12) extend this table: closure parameters that
vary over a surface get resolved per hit in ``materials.resolve`` into the same row layout.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from ..bsdf.closure import (C_ALPHA, C_COAT_IOR, C_COAT_NM, C_FILM_IOR, C_FILM_NM, C_GLASS, C_K, C_KIND, C_N,
                            C_SPECTRUM, C_WEIGHT, CLOSURE_ROW, CONDUCTOR, DIELECTRIC, DIFFUSE, SMOOTH_ALPHA,
                            THIN_FILM)
from ..errors import PrismInputError
from ..scene import SpectrumSpec
from ..spectra.dispersion import GLASS_ROW, glass_row

MAT_DELTA = 1
MAT_DISPERSIVE = 2
MAT_NULL = 4
MAT_ONE_SIDED = 8
MAT_EMISSIVE = 16

MaterialArrays = namedtuple(
    "MaterialArrays", "flags closure_start closure_count emission_spectrum emission_strength closures glasses"
)


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


@dataclass
class MaterialTable:
    """Rows for the materials a render uses (unused ones get an empty entry), and what they need."""

    arrays: MaterialArrays
    glasses: list = field(default_factory=list)  # the Glass object of each glass row (names, warnings)
    features: list = field(default_factory=list)  # e.g. "smooth dielectric", for the render stats


def _base_reflectance(material, spectra) -> int:
    """Spectrum id of what the material uses as base colour: a measured reflectance or the RGB one."""
    if material.reflectance is not None:
        return spectra.measured_reflectance(material.reflectance, f"Material '{material.name}'")
    return spectra.reflectance(material.base_color)


def _closure(material, spectra, glasses, glass_index):
    row = np.full(CLOSURE_ROW, -1.0)
    row[[C_WEIGHT, C_ALPHA, C_COAT_NM, C_COAT_IOR, C_FILM_NM, C_FILM_IOR]] = (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)
    kind = material.kind
    if kind == "diffuse":
        row[C_KIND] = DIFFUSE
        row[C_SPECTRUM] = _base_reflectance(material, spectra)
        return row, "diffuse"
    if kind in ("conductor", "dielectric"):
        row[C_ALPHA] = _alpha(material)
        if material.coating_thickness_nm > 0:
            row[C_COAT_NM] = float(material.coating_thickness_nm)
            row[C_COAT_IOR] = float(material.coating_ior)
            if not row[C_COAT_IOR] > 0:
                raise PrismInputError(
                    f"Material '{material.name}': the coating's IOR must be positive (got {material.coating_ior})."
                )
        smooth = row[C_ALPHA] < SMOOTH_ALPHA
    if kind == "conductor":
        row[C_KIND] = CONDUCTOR
        if material.conductor:
            from ..spectra.conductors import _lookup

            table_nm, n, k = _lookup(material.conductor)
            row[C_N] = spectra.resampled(("n", material.conductor), table_nm, n)
            row[C_K] = spectra.resampled(("k", material.conductor), table_nm, k)
        else:
            row[C_SPECTRUM] = _base_reflectance(material, spectra)
        return row, ("mirror conductor" if smooth else "rough conductor")
    if kind == "dielectric":
        row[C_KIND] = DIELECTRIC
        glass = glass_of(material)
        key = id(glass)
        if key not in glass_index:
            glass_index[key] = len(glasses)
            glasses.append(glass)
        row[C_GLASS] = glass_index[key]
        return row, ("smooth dielectric" if smooth else "rough dielectric")
    if kind == "thin_film":
        if not (material.film_thickness_nm >= 0 and material.film_ior > 0):
            raise PrismInputError(f"Material '{material.name}': film thickness and IOR must be positive.")
        row[C_KIND] = THIN_FILM
        row[C_FILM_NM] = float(material.film_thickness_nm)
        row[C_FILM_IOR] = float(material.film_ior)
        return row, "thin_film"
    raise PrismInputError(
        f"Material '{material.name}': unknown kind '{kind}'; use diffuse, conductor, dielectric or thin_film."
    )


def build_materials(materials, used, spectra) -> MaterialTable:
    """Tables for ``materials`` (``scene.Material``); only indices in ``used`` get closures.
    ``spectra`` is the render's ``SpectrumTable``."""
    count = len(materials)
    flags = np.zeros(count, np.int32)
    start = np.zeros(count, np.int32)
    closure_count = np.zeros(count, np.int32)
    emission_spectrum = np.zeros(count, np.int32)
    emission_strength = np.zeros(count)
    rows, glasses, glass_index, features = [], [], {}, set()
    for m, material in enumerate(materials):
        if m not in used:
            continue
        row, feature = _closure(material, spectra, glasses, glass_index)
        features.add(feature)
        start[m], closure_count[m] = len(rows), 1
        rows.append(row)
        if material.kind in ("conductor", "dielectric") and material.coating_thickness_nm > 0:
            features.add("thin-film coating")
        if row[C_KIND] == THIN_FILM or (row[C_KIND] != DIFFUSE and row[C_ALPHA] < SMOOTH_ALPHA):
            flags[m] |= MAT_DELTA
        if material.kind == "thin_film":
            flags[m] |= MAT_NULL
        if material.kind == "dielectric":
            flags[m] |= MAT_ONE_SIDED
            if glasses[int(row[C_GLASS])].is_dispersive:
                flags[m] |= MAT_DISPERSIVE
        if is_emissive(material):
            flags[m] |= MAT_EMISSIVE
            try:
                emission_spectrum[m] = spectra.emission(material.emission or SpectrumSpec())
            except PrismInputError as error:
                raise PrismInputError(f"Material '{material.name}': {error}") from None
            emission_strength[m] = float(material.emission_strength)
    closures = np.array(rows, dtype=np.float64).reshape(-1, CLOSURE_ROW)
    glass_rows = np.array([glass_row(g) for g in glasses] or [glass_row(None)]).reshape(-1, GLASS_ROW)
    arrays = MaterialArrays(flags, start, closure_count, emission_spectrum, emission_strength,
                            closures if len(closures) else np.zeros((1, CLOSURE_ROW)), glass_rows)
    return MaterialTable(arrays, glasses, sorted(features))
