"""Emission of a grid medium as rows of spectra over a grid's values, for the kernels to interpolate
(``grid_emission``).

Cycles' Principled Volume emits Emission Strength × Emission Color per metre, and blackbody light of
σ_SB 10⁻⁶ / π × mix(1, T⁴, Blackbody Intensity) × Blackbody Tint × the luminance-1 blackbody colour at T,
where T = Temperature × max(v, 0) and v the value of the grid its Temperature Attribute names (Cycles'
``svm_node_principled_volume``; T = Temperature where there is no such grid). The emission is then a
function of v alone, so it is tabulated here once per medium: ``ROWS`` spectra at v = 0, step, 2 step, ...
up to the grid's largest value, on the 1 nm grid, linear between rows. Midway between rows, 256 rows stay
within 2.3·10⁻⁵ of the exact emission at the hottest voxels and 9.2·10⁻⁵ over the upper half of the grid's
values (Temperature 1000, 1500 and 3000 K; measured against ``blackbody_intensity`` × ``tinted_blackbody``). Planck's spectrum is coloured
at T clamped to ``MIN_TEMPERATURE_K``-``MAX_TEMPERATURE_K`` (below 1000 K the light is dim; Cycles holds its
colour below 800 K), at the intensity of T itself.
"""

from __future__ import annotations

import math

import numpy as np

from ..spectra.tinted_blackbody import tinted_blackbody

STEFAN_BOLTZMANN = 5.670373e-8  # W m⁻² K⁻⁴, the value Cycles' Principled Volume uses

#: Spectra tabulated over a temperature grid's values.
ROWS = 256


def blackbody_intensity(temperature_k, blend):
    """Cycles' blackbody scale of a Principled Volume, σ_SB 10⁻⁶ / π × mix(1, T⁴, ``blend``) (any shape)."""
    t = np.maximum(np.asarray(temperature_k, dtype=np.float64), 0.0)
    return STEFAN_BOLTZMANN * 1e-6 / math.pi * (1.0 + blend * (t ** 4 - 1.0))


def emission_rows(spec) -> tuple[np.ndarray, float]:
    """(rows [R, len(VISIBLE_NM_GRID)] of emitted radiance per metre, the grid value per row) of a
    ``MediumSpec`` with an emitting grid: row r holds the emission where that grid reads r × step, its
    constant terms (Emission Strength × Color) in every row. A temperature grid's rows follow Planck's law; a
    strength grid's (``MediumSpec.emission_field``) are linear in its value, so two rows are exact."""
    from dataclasses import replace

    from .table import emission_on_grid

    if spec.temperature_grid is None:
        largest = max(float(np.max(spec.strength_grid.values)), 0.0)
        per_unit = emission_on_grid(replace(spec, emission=[(w, rgb, None) for w, rgb in spec.emission_field]))
        values = np.array([0.0, largest])
        rows = emission_on_grid(spec)[None, :] + values[:, None] * per_unit[None, :]
        return np.maximum(rows, 0.0), largest if largest > 0.0 else 1.0
    constant = emission_on_grid(replace(spec, emission=[e for e in spec.emission if e[2] is None]))
    largest = float(np.max(np.maximum(spec.temperature_grid.values, 0.0)))
    count = ROWS if largest > 0.0 else 1
    step = largest / (count - 1) if count > 1 else 1.0
    values = np.arange(count) * step
    rows = np.repeat(constant[None, :], count, axis=0)
    for weight, blend, temperature_k, tint in spec.blackbody:
        temperature = temperature_k * values
        rows += (weight * blackbody_intensity(temperature, blend))[:, None] * tinted_blackbody(temperature, tint)
    return np.maximum(rows, 0.0), step


def emission_key(spec) -> tuple:
    """What ``emission_rows`` depends on, for sharing one table between instances of one Volume object."""
    grid = spec.emitting_grid
    return (tuple(e for e in spec.emission if e[2] is None), tuple(spec.blackbody), tuple(spec.emission_field),
            spec.temperature_grid is None, float(np.max(np.maximum(grid.values, 0.0))) if grid is not None else None)
