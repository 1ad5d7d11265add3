"""Blender's Multiscatter GGX: the energy a single-scattering GGX lobe misses, given back as a scale.

A GGX lobe scatters once; light that the microfacets would scatter again is lost, so a rough white lobe
reflects less than it receives (E(μ) < 1). Energy compensation (Kulla & Conty, "Revisiting Physically
Based Shading at Imageworks", SIGGRAPH 2017 course; Turquin, "Practical multiple scattering compensation
for microfacet models", 2019), as Cycles applies it to closures whose distribution is Multiscatter GGX
(``bsdf_microfacet.h``, ``microfacet_ggx_preserve_energy``), multiplies the single-scattering lobe by

    1 + Fms (1 - E(μ)) / E(μ),    Fms = Fss E_avg / (1 - Fss (1 - E_avg)),

with μ the view cosine, E the lobe's directional albedo (F = 1 for a reflection; reflection plus
refraction with the exact dielectric Fresnel for glass, per η), E_avg its cosine-weighted average, and
Fss the lobe's average single-scattering Fresnel (the colour of a Glossy or Glass node, the average of a
conductor's Fresnel per wavelength). The scale depends on the view direction only, so it is applied to
the closure's tint where the material is resolved at a hit (``materials.energy``): evaluate and sample
weights both carry it, pdfs are unchanged.

Tables (``EnergyTables``, computed by ``tools/generate_ggx_energy.py`` into ``data/ggx_energy.npz``)
sit on Cycles' grids and are read with its linear interpolation. Roughness r = √alpha.
"""

from __future__ import annotations

import math
from collections import namedtuple
from pathlib import Path

import numpy as np

from ..jit import kernel
from ..table_files import load_table
from .closure import C_ETA, C_FRESNEL, FRESNEL_CONDUCTOR, FRESNEL_DIELECTRIC, FRESNEL_F82, FRESNEL_SCHLICK
from .conductor import C82_5, C82_WEIGHT
from .optics import dielectric_f0, fresnel_conductor, tinted_fresnel

TABLE_PATH = Path(__file__).resolve().parent / "data" / "ggx_energy.npz"

#: ``ggx_e`` [R, M] and ``ggx_e_avg`` [R]: GGX reflection with F = 1 (roughness, view cosine, each uniform
#: over 0-1); ``glass_e`` [R, M, Z] and ``glass_e_avg`` [R, Z]: a rough dielectric interface seen from
#: index 1 towards η > 1, z = √|(η - 1)/(η + 1)| uniform over 0-1; ``glass_inv_e`` / ``glass_inv_e_avg``: the
#: same towards 1/η (from inside); ``dielectric_fss`` [Z]: a dielectric's average Fresnel 2 ∫ F(μ) μ dμ for
#: η > 1 on a uniform z grid. All float64.
EnergyTables = namedtuple("EnergyTables",
                          "ggx_e ggx_e_avg glass_e glass_e_avg glass_inv_e glass_inv_e_avg dielectric_fss")

#: Gauss-Legendre nodes and weights on [0, 1] for a conductor's average Fresnel (2 ∫ F μ dμ to < 1e-5).
_X, _W = np.polynomial.legendre.leggauss(12)
_GL_NODES = tuple(float(x) for x in 0.5 * (_X + 1.0))
_GL_WEIGHTS = tuple(float(w) for w in 0.5 * _W)


def load_energy_tables() -> EnergyTables:
    return load_table(TABLE_PATH, EnergyTables)


@kernel
def grid_cell(x, n):
    """(cell, fraction) of ``x`` on a uniform grid of ``n`` points over 0-1 (clamped)."""
    x = min(max(x, 0.0), 1.0) * (n - 1)
    i = min(int(x), n - 2)
    return i, x - i


@kernel
def _lerp1(table, x):
    i, f = grid_cell(x, table.shape[0])
    return (1.0 - f) * table[i] + f * table[i + 1]


@kernel
def _lerp2(table, x, y):
    i, fi = grid_cell(x, table.shape[0])
    j, fj = grid_cell(y, table.shape[1])
    return ((1.0 - fi) * ((1.0 - fj) * table[i, j] + fj * table[i, j + 1])
            + fi * ((1.0 - fj) * table[i + 1, j] + fj * table[i + 1, j + 1]))


@kernel
def _lerp3(table, x, y, z):
    k, fk = grid_cell(z, table.shape[2])
    s = 0.0
    for dk in range(2):
        w = fk if dk else 1.0 - fk
        i, fi = grid_cell(x, table.shape[0])
        j, fj = grid_cell(y, table.shape[1])
        s += w * ((1.0 - fi) * ((1.0 - fj) * table[i, j, k + dk] + fj * table[i, j + 1, k + dk])
                  + fi * ((1.0 - fj) * table[i + 1, j, k + dk] + fj * table[i + 1, j + 1, k + dk]))
    return s


@kernel
def index_z(eta):
    """The tables' parameter z = √|(η - 1)/(η + 1)| of a relative index ``eta`` ≥ 1."""
    return math.sqrt(abs((eta - 1.0) / (eta + 1.0)))


@kernel
def reflection_albedo(tables, rough, mu):
    """(E(μ), E_avg) of GGX reflection with F = 1 at roughness ``rough`` = √alpha and view cosine ``mu``."""
    return _lerp2(tables.ggx_e, rough, mu), _lerp1(tables.ggx_e_avg, rough)


@kernel
def glass_albedo(tables, rough, mu, eta):
    """(E(μ), E_avg) of a rough dielectric interface (reflection + refraction, as energy) of relative index
    ``eta`` (index behind / index in front; < 1 seen from inside)."""
    if eta < 1.0:
        z = index_z(1.0 / eta)
        return _lerp3(tables.glass_inv_e, rough, mu, z), _lerp2(tables.glass_inv_e_avg, rough, z)
    z = index_z(eta)
    return _lerp3(tables.glass_e, rough, mu, z), _lerp2(tables.glass_e_avg, rough, z)


@kernel
def dielectric_fss(tables, eta):
    """Average Fresnel 2 ∫ F(μ) μ dμ of a dielectric interface of relative index ``eta``. Below 1, by
    reciprocity (equal radiance n² on both sides in equilibrium): F_avg(1/η) = 1 - (1 - F_avg(η)) / η²."""
    if eta >= 1.0:
        return _lerp1(tables.dielectric_fss, index_z(eta))
    inverse = 1.0 / eta
    return 1.0 - (1.0 - _lerp1(tables.dielectric_fss, index_z(inverse))) * eta * eta


@kernel
def conductor_fss(n, k):
    """Average Fresnel 2 ∫ F(μ) μ dμ of a conductor of complex index n + ik (Gauss-Legendre; exact per
    wavelength, where Cycles fits an F82 curve to F(0°) and F(82°))."""
    total = 0.0
    for i in range(len(_GL_NODES)):
        mu = _GL_NODES[i]
        total += _GL_WEIGHTS[i] * mu * fresnel_conductor(mu, n, k)
    return 2.0 * total


@kernel
def model_fss(tables, row, spectral, k):
    """Fss at wavelength column ``k`` of a reflection closure whose Fresnel model sets it; -1 where the
    closure's multiscatter colour does (F = 1: Glossy). Thin-film coatings are left out, as in Cycles."""
    mode = int(row[C_FRESNEL])
    if mode == FRESNEL_CONDUCTOR:
        return conductor_fss(spectral[0, k], spectral[1, k])
    if mode == FRESNEL_DIELECTRIC:
        eta = row[C_ETA]
        # Specular Tint remaps F from [F0, 1] to [F0 tint, 1], a linear map that commutes with the average
        return tinted_fresnel(dielectric_fss(tables, eta), dielectric_f0(eta), spectral[0, k], False)
    f0 = spectral[0, k]
    if mode == FRESNEL_F82:
        # 2 ∫ μ (1 - μ)^5 dμ = 1/21 and 2 ∫ μ² (1 - μ)^6 dμ = 1/126 (see conductor.reflectance)
        b = (f0 + (1.0 - f0) * C82_5) * (1.0 - spectral[1, k]) / C82_WEIGHT
        return min(max(f0 + (1.0 - f0) / 21.0 - b / 126.0, 0.0), 1.0)
    if mode == FRESNEL_SCHLICK:
        return f0 + (1.0 - f0) / 21.0
    return -1.0


@kernel
def energy_scale(fss, e, e_avg):
    """1 + Fms (1 - E)/E: the factor on a single-scattering lobe of albedo ``e`` (and average ``e_avg``)
    whose average single-scattering Fresnel is ``fss`` (Kulla & Conty 2017, appendix; one Fss cancels,
    the lobe already holds one bounce of Fresnel)."""
    if not (e > 0.0 and e < 1.0):
        return 1.0
    fss = min(max(fss, 0.0), 1.0)
    fms = fss * e_avg / (1.0 - fss * (1.0 - e_avg))
    return 1.0 + fms * (1.0 - e) / e
