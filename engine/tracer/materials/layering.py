"""Albedo of a layer, for weighting what lies under it (Blender's Principled BSDF layering).

Blender lets the sheen, coat and specular layers take their share first: the closures below are
weighted by 1 - albedo(view) of the layer above (the sheen's fitted albedo: ``bsdf.sheen``, ``SHEEN_ALBEDO``). For a GGX reflection whose dielectric Fresnel (index
η) is remapped to start at a tinted f0, albedo = mix(f0, 1, s(roughness, μ, η)), with s tabulated by
``tools/generate_layer_albedo.py`` (``data/ggx_layer_albedo.npz``) and read here trilinearly. A Multiscatter
GGX layer (the coat always, the specular layer when the node asks) reflects what its energy compensation
gives, mix(f0, 1, s) E (1 + Fms (1 - E)/E) (``dielectric_darkening``), as Cycles weighs it.

A layer whose parameters are constant is stored in the rows of the closures under it (``bsdf.closure``
``C_LAYER_*``) and applied here (``under_layer``); a varying one is computed by the material's program.
"""

from __future__ import annotations

import math
from collections import namedtuple
from pathlib import Path

import numpy as np

from ..bsdf.closure import C_LAYER_ETA, C_LAYER_F0, C_LAYER_MULTISCATTER, C_LAYER_ROUGHNESS
from ..bsdf.multiscatter import dielectric_fss, energy_scale, grid_cell, load_energy_tables, reflection_albedo
from ..bsdf.optics import dielectric_f0
from ..bsdf.sheen import load_sheen_table
from ..jit import kernel

TABLE_PATH = Path(__file__).resolve().parent / "data" / "ggx_layer_albedo.npz"

#: ``dielectric_s`` float64 [R, M, Z] (roughness, view cosine, √|(η-1)/(η+1)|, each uniform over 0-1);
#: ``energy``: the GGX energy tables of Multiscatter GGX (``bsdf.multiscatter.EnergyTables``) and ``sheen``: the
#: microfiber sheen fit (``bsdf.sheen.SheenTable``), which travel with these to the kernels.
LayerTables = namedtuple("LayerTables", "dielectric_s energy sheen")

_CACHE = {}


def load_tables() -> LayerTables:
    if "tables" not in _CACHE:
        with np.load(TABLE_PATH) as data:
            _CACHE["tables"] = LayerTables(np.ascontiguousarray(data["dielectric_s"], dtype=np.float64),
                                           load_energy_tables(), load_sheen_table())
    return _CACHE["tables"]


@kernel
def dielectric_s(tables, roughness, cos_view, eta):
    """s of a GGX dielectric reflection of Blender ``roughness`` seen at ``cos_view``."""
    table = tables.dielectric_s
    if not (math.isfinite(roughness) and math.isfinite(cos_view) and eta > 0.0):
        return 0.0
    z = math.sqrt(abs((eta - 1.0) / (eta + 1.0)))
    i, fi = grid_cell(roughness, table.shape[0])
    j, fj = grid_cell(abs(cos_view), table.shape[1])
    k, fk = grid_cell(z, table.shape[2])
    s = 0.0
    for di in range(2):
        wi = fi if di else 1.0 - fi
        for dj in range(2):
            wj = wi * (fj if dj else 1.0 - fj)
            for dk in range(2):
                s += wj * (fk if dk else 1.0 - fk) * table[i + di, j + dj, k + dk]
    return s


@kernel
def dielectric_darkening(tables, roughness, cos_view, eta, f0):
    """Factor on the energy-preserving albedo mix(f0, 1, s) of a Multiscatter GGX dielectric layer of Blender
    ``roughness`` and normal-incidence reflectance ``f0`` (Specular Tint included): what the compensated
    lobe reflects, E (1 + Fms (1 - E)/E) (``bsdf.multiscatter``), below 1 when Fss < 1. Cycles weighs the
    layers below with this albedo (``bsdf_albedo`` of the compensated closure)."""
    if not (roughness > 0.0 and eta > 0.0):
        return 1.0
    e, e_avg = reflection_albedo(tables.energy, roughness, abs(cos_view))
    f0_real = dielectric_f0(eta)
    s = (dielectric_fss(tables.energy, eta) - f0_real) / (1.0 - f0_real) if f0_real < 1.0 else 1.0
    fss = f0 + (1.0 - f0) * min(max(s, 0.0), 1.0)
    return e * energy_scale(fss, e, e_avg)


@kernel
def under_layer(tables, row, cos_view):
    """Fraction of the light a closure receives under the constant layer of its ``row`` (1 without one):
    1 - albedo, with the albedo's largest channel f0 + (1 - f0) s (times ``dielectric_darkening`` for a
    Multiscatter GGX layer), clamped to 0-1."""
    eta = row[C_LAYER_ETA]
    if not eta > 0.0:
        return 1.0
    f0 = row[C_LAYER_F0]
    s = dielectric_s(tables, row[C_LAYER_ROUGHNESS], cos_view, eta)
    albedo = f0 + (1.0 - f0) * s
    if row[C_LAYER_MULTISCATTER] > 0.0:
        albedo *= dielectric_darkening(tables, row[C_LAYER_ROUGHNESS], cos_view, eta, f0)
    return min(max(1.0 - albedo, 0.0), 1.0)
