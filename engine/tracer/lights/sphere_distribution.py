"""A piecewise-constant distribution of directions over the cells of an equirectangular grid.

Blender's equirectangular layout: a direction (x, y, z) has u = (π - atan2(y, x)) / 2π (the image's
horizontal coordinate, 0.5 at +X) and polar angle θ = acos z; the grid has H rows (row 0 at the zenith,
row i covering θ in [iπ/H, (i+1)π/H]) and W columns (column j covering u in [j/W, (j+1)/W]).

A cell is chosen with probability ∝ its weight (``build_sphere_distribution``: the weight of a cell is
its mean radiance-like value times its solid angle), then a direction uniformly *in solid angle* within
it (u uniform, z = cos θ uniform between the row's edges), so the density is cell_prob / Ω_cell with no
singularity at the poles. ``SphereDistribution``: ``marginal_cdf`` float64 [H] (rows),
``conditional_cdf`` float64 [H, W] (columns within each row), ``cell_prob`` float64 [H, W], ``z_edges``
float64 [H + 1] (cos θ of the row edges, 1 → -1).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import kernel
from ..warps import cdf_index

SphereDistribution = namedtuple("SphereDistribution", "marginal_cdf conditional_cdf cell_prob z_edges")


def row_z_edges(rows: int) -> np.ndarray:
    """cos θ at the edges of ``rows`` equal-angle rows, from the zenith (1) to the nadir (-1)."""
    z = np.cos(np.linspace(0.0, math.pi, rows + 1))
    z[0], z[-1] = 1.0, -1.0
    return z


def cell_solid_angles(rows: int, columns: int) -> np.ndarray:
    """Solid angle (sr) of each cell, [rows] (the same for every column)."""
    z = row_z_edges(rows)
    return (z[:-1] - z[1:]) * (2.0 * math.pi / columns)


def build_sphere_distribution(mean_value) -> SphereDistribution:
    """The distribution of an [H, W] grid of non-negative mean values per cell (e.g. luminance):
    cell probabilities ∝ value × solid angle; uniform over the sphere when every value is 0."""
    value = np.nan_to_num(np.asarray(mean_value, np.float64), nan=0.0, posinf=0.0)
    value = np.maximum(value, 0.0)
    rows, columns = value.shape
    weight = value * cell_solid_angles(rows, columns)[:, None]
    if not weight.sum() > 0.0:
        weight = np.broadcast_to(cell_solid_angles(rows, columns)[:, None], (rows, columns)).copy()
    cell_prob = weight / weight.sum()
    row_prob = cell_prob.sum(axis=1)
    marginal = np.cumsum(row_prob)
    marginal /= marginal[-1]
    conditional = np.cumsum(weight, axis=1)
    totals = conditional[:, -1:].copy()
    empty = totals[:, 0] <= 0.0
    conditional[empty] = np.arange(1, columns + 1) / columns
    totals[empty] = 1.0
    conditional /= totals
    conditional[:, -1] = 1.0
    return SphereDistribution(np.ascontiguousarray(marginal), np.ascontiguousarray(conditional),
                              np.ascontiguousarray(cell_prob), row_z_edges(rows))


@kernel
def _search(cdf, u):
    """First index whose cdf value exceeds ``u`` (cdf ends at 1), and u rescaled within that interval."""
    lo = cdf_index(cdf, u)
    below = cdf[lo - 1] if lo > 0 else 0.0
    width = cdf[lo] - below
    rest = (u - below) / width if width > 0.0 else 0.5
    return lo, min(max(rest, 0.0), 0.9999999999999999)


@kernel
def direction_to_cell(dist, d):
    """(row, column, u, cos θ) of unit direction ``d`` in the grid of ``dist``."""
    rows = dist.cell_prob.shape[0]
    columns = dist.cell_prob.shape[1]
    z = min(max(d[2], -1.0), 1.0)
    u = (math.pi - math.atan2(d[1], d[0])) / (2.0 * math.pi)
    row = min(int(math.acos(z) / math.pi * rows), rows - 1)
    column = min(max(int(u * columns), 0), columns - 1)
    return row, column, u, z


@kernel
def sample_direction(dist, u1, u2):
    """(unit direction, solid-angle density) drawn from ``dist`` with two uniforms."""
    row, v = _search(dist.marginal_cdf, u1)
    column, w = _search(dist.conditional_cdf[row], u2)
    columns = dist.cell_prob.shape[1]
    z_top = dist.z_edges[row]
    z_bottom = dist.z_edges[row + 1]
    z = z_top + v * (z_bottom - z_top)
    u = (column + w) / columns
    phi = math.pi - 2.0 * math.pi * u
    r = math.sqrt(max(0.0, 1.0 - z * z))
    omega = (z_top - z_bottom) * (2.0 * math.pi / columns)
    return (r * math.cos(phi), r * math.sin(phi), z), dist.cell_prob[row, column] / omega


@kernel
def direction_pdf(dist, d):
    """Solid-angle density of ``sample_direction`` at unit direction ``d``."""
    row, column, _, _ = direction_to_cell(dist, d)
    columns = dist.cell_prob.shape[1]
    omega = (dist.z_edges[row] - dist.z_edges[row + 1]) * (2.0 * math.pi / columns)
    return dist.cell_prob[row, column] / omega if omega > 0.0 else 0.0
