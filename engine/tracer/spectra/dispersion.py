"""Refractive indices inside kernels: every glass as one row of numbers, evaluated per wavelength.

A glass row (float64 [GLASS_ROW]) is ``kind, valid_min_nm, valid_max_nm, p0 .. p5``:

- ``GLASS_CONSTANT``: n = p0 at every wavelength (air is the constant 1);
- ``GLASS_SELLMEIER``: n² = 1 + Σ B_i λ² / (λ² - C_i), λ in µm, with B = p0..p2 and C = p3..p5 (µm²);
- ``GLASS_CAUCHY``: n = A + B / λ², λ in nm, A = p0, B = p1 (nm²).

Outside the valid range the index is that at the nearest edge (as ``glass.Glass.index``); the kernel
function says so, so renders can count clamped samples. Rows are built from the ``glass`` module's
objects by ``glass_row``; that module stays the reference (catalogue, validation, n_d/V_d).
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel

GLASS_CONSTANT = 0
GLASS_SELLMEIER = 1
GLASS_CAUCHY = 2
GLASS_ROW = 9


def glass_row(glass) -> np.ndarray:
    """The kernel row of a ``glass.Glass`` (Sellmeier, Cauchy or constant) or of air (None)."""
    from .glass import CauchyGlass, ConstantGlass, SellmeierGlass

    row = np.zeros(GLASS_ROW)
    if glass is None:
        row[:4] = (GLASS_CONSTANT, 0.0, math.inf, 1.0)
    elif isinstance(glass, ConstantGlass):
        row[:4] = (GLASS_CONSTANT, 0.0, math.inf, glass.ior)
    elif isinstance(glass, SellmeierGlass):
        row[:3] = (GLASS_SELLMEIER, *glass.valid_range_nm)
        row[3:6] = glass.b
        row[6:9] = glass.c_um2
    elif isinstance(glass, CauchyGlass):
        row[:5] = (GLASS_CAUCHY, *glass.valid_range_nm, glass.a, glass.b_nm2)
    else:
        raise TypeError(f"No kernel form for glass {glass!r}")
    return row


@kernel
def refractive_index(row, wavelength_nm):
    """(index, clamped) of glass ``row`` at ``wavelength_nm``; ``clamped`` when outside the valid range."""
    kind = int(row[0])
    if kind == GLASS_CONSTANT:
        return row[3], False
    lam = wavelength_nm
    clamped = False
    if lam < row[1]:
        lam = row[1]
        clamped = True
    elif lam > row[2]:
        lam = row[2]
        clamped = True
    if kind == GLASS_SELLMEIER:
        l2 = (lam * 1e-3) * (lam * 1e-3)
        n2 = 1.0 + row[3] * l2 / (l2 - row[6]) + row[4] * l2 / (l2 - row[7]) + row[5] * l2 / (l2 - row[8])
        return math.sqrt(n2), clamped
    return row[3] + row[4] / (lam * lam), clamped


@kernel
def is_dispersive(row):
    return int(row[0]) != GLASS_CONSTANT
