"""Colours computed per hit (textures, node programs) → spectra at the path's wavelengths, in kernels.

Constant colours are upsampled once per render by ``rgb_to_spectrum`` (Jakob-Hanika coefficients,
polished per colour). A colour that varies over a surface is known only at a hit, so the kernels look
its coefficients up in a dense table of the same fits (``tools/generate_rgb_lut.py``) by trilinear
interpolation (as pbrt-v4 does) and evaluate the sigmoid at the carried wavelengths: no Python per
ray, and constant and textured colours share one upsampling.

Grid (``grid``): the largest channel c of the colour, its value z on a smoothstep-of-smoothstep grid
(dense near 0 and 1), and the ratios x = rgb[c+1] / z, y = rgb[c+2] / z on a uniform grid. Below the
first grid value the spectrum of the same chromaticity is scaled down linearly; colours above 1 (weights,
emission) use pbrt's unbounded form: scale s = 2 max(rgb), spectrum s · S(rgb / s).
"""

from __future__ import annotations

import math
from collections import namedtuple
from pathlib import Path

import numpy as np

from ..jit import kernel
from .table import sigmoid_polynomial

LUT_SIZE = 32
LUT_PATH = Path(__file__).resolve().parent / "data" / f"rec709_sigmoid_lut{LUT_SIZE}.npz"
_Z_FLOOR = 1e-6  # the grid's first value (black itself has no finite coefficients)
_Z_CEILING = 1.0 - 1e-6  # its last (white neither)

#: ``coefficients`` float64 [3, N, N, N, 3] (c0 /nm², c1 /nm, c2 per largest channel, z, y, x), ``z_grid`` [N].
RGBLut = namedtuple("RGBLut", "coefficients z_grid")

_CACHE = {}


def grid(n: int):
    """(z values [n], ratio values [n]) of a table of size ``n``."""
    t = np.linspace(0.0, 1.0, n)
    z = t * t * (3.0 - 2.0 * t)
    z = z * z * (3.0 - 2.0 * z)
    z[0], z[-1] = _Z_FLOOR, _Z_CEILING
    return z, np.linspace(0.0, 1.0, n)


def load_lut() -> RGBLut:
    """The committed table, in nm units, for the kernels (loaded once per process)."""
    if "lut" not in _CACHE:
        from .rgb_to_spectrum import _to_nm_domain

        with np.load(LUT_PATH) as data:
            unit = data["coefficients"].astype(np.float64)
            z_grid = np.ascontiguousarray(data["z_grid"], dtype=np.float64)
        _CACHE["lut"] = RGBLut(np.ascontiguousarray(_to_nm_domain(unit)), z_grid)
    return _CACHE["lut"]


def empty_lut() -> RGBLut:
    """A placeholder for renders whose colours are all constant (nothing is looked up)."""
    return RGBLut(np.zeros((3, 2, 2, 2, 3)), np.array([0.0, 1.0]))


@kernel
def _find_z(z_grid, z):
    lo, hi = 0, z_grid.shape[0] - 2
    while lo < hi:
        mid = (lo + hi + 1) >> 1
        if z_grid[mid] <= z:
            lo = mid
        else:
            hi = mid - 1
    return lo


@kernel
def bounded_coefficients(lut, r, g, b):
    """(c0, c1, c2, scale) of a reflectance colour with components in [0, 1]: spectrum = scale ·
    S(λ; c). scale is 1 except below the grid (dark colours keep their chromaticity)."""
    if r >= g and r >= b:
        channel, z, x, y = 0, r, g, b
    elif g >= b:
        channel, z, x, y = 1, g, b, r
    else:
        channel, z, x, y = 2, b, r, g
    if not z > 0.0:
        return 0.0, 0.0, -1e10, 0.0
    scale = 1.0
    x = min(max(x / z, 0.0), 1.0)
    y = min(max(y / z, 0.0), 1.0)
    z_grid = lut.z_grid
    if z < z_grid[0]:
        scale = z / z_grid[0]
        z = z_grid[0]
    z = min(z, z_grid[z_grid.shape[0] - 1])
    n = z_grid.shape[0]
    zi = _find_z(z_grid, z)
    fz = (z - z_grid[zi]) / (z_grid[zi + 1] - z_grid[zi])
    xf = x * (n - 1)
    yf = y * (n - 1)
    xi = min(int(xf), n - 2)
    yi = min(int(yf), n - 2)
    fx = xf - xi
    fy = yf - yi
    table = lut.coefficients[channel]
    c0 = 0.0
    c1 = 0.0
    c2 = 0.0
    for dz in range(2):
        wz = fz if dz else 1.0 - fz
        for dy in range(2):
            wy = wz * (fy if dy else 1.0 - fy)
            for dx in range(2):
                w = wy * (fx if dx else 1.0 - fx)
                cell = table[zi + dz, yi + dy, xi + dx]
                c0 += w * cell[0]
                c1 += w * cell[1]
                c2 += w * cell[2]
    return c0, c1, c2, scale


@kernel
def table_coefficients(lut, rgb, out):
    """``out[i]`` = the table's (c0, c1, c2) of reflectance ``rgb[i]`` (components in [0, 1]): the first
    guesses ``rgb_to_spectrum`` polishes, one call for a render's constant colours."""
    for i in range(rgb.shape[0]):
        c0, c1, c2, _ = bounded_coefficients(lut, rgb[i, 0], rgb[i, 1], rgb[i, 2])
        out[i, 0] = c0
        out[i, 1] = c1
        out[i, 2] = c2


@kernel
def reflectance_values(lut, r, g, b, wavelengths_nm, out):
    """``out[k]`` = the reflectance spectrum of linear Rec.709 (r, g, b) (clamped to [0, 1]) at
    ``wavelengths_nm[k]``."""
    r = min(max(r, 0.0), 1.0) if math.isfinite(r) else 0.0
    g = min(max(g, 0.0), 1.0) if math.isfinite(g) else 0.0
    b = min(max(b, 0.0), 1.0) if math.isfinite(b) else 0.0
    if r == g and g == b:
        for k in range(out.shape[0]):
            out[k] = r
        return
    c0, c1, c2, scale = bounded_coefficients(lut, r, g, b)
    for k in range(out.shape[0]):
        out[k] = scale * sigmoid_polynomial(c0, c1, c2, wavelengths_nm[k])


@kernel
def unbounded_values(lut, r, g, b, wavelengths_nm, out):
    """``out[k]`` = a smooth spectrum of linear Rec.709 (r, g, b) ≥ 0 of any magnitude (closure
    weights, emission colours): s · S(λ; rgb / s) with s = 2 max(rgb) when max(rgb) > 1."""
    r = max(r, 0.0) if math.isfinite(r) else 0.0
    g = max(g, 0.0) if math.isfinite(g) else 0.0
    b = max(b, 0.0) if math.isfinite(b) else 0.0
    largest = max(r, g, b)
    if largest <= 1.0:
        reflectance_values(lut, r, g, b, wavelengths_nm, out)
        return
    s = 2.0 * largest
    reflectance_values(lut, r / s, g / s, b / s, wavelengths_nm, out)
    for k in range(out.shape[0]):
        out[k] *= s
