"""Reading a density grid in compiled code (``density_grid.GridArrays``): where a ray crosses its bounds,
and the trilinear density at a point of the ray.

A ray o + s d (relative to the render's origin, ``d`` unit) maps to index space as o' + s d' with o' = A o +
b and d' = A d (the grid's affine ``world_to_index``), so distances along the ray are the same in both
spaces and the kernels step in metres while they look voxels up in index coordinates.
"""

from __future__ import annotations

import math

from ..jit import inlined, kernel


@kernel
def index_ray(grids, g, o, d):
    """(o', d'): the ray ``o`` + s ``d`` in grid ``g``'s index coordinates (same parameter s)."""
    m = grids.world_to_index[g]
    o2 = (m[0, 0] * o[0] + m[0, 1] * o[1] + m[0, 2] * o[2] + m[0, 3],
          m[1, 0] * o[0] + m[1, 1] * o[1] + m[1, 2] * o[2] + m[1, 3],
          m[2, 0] * o[0] + m[2, 1] * o[1] + m[2, 2] * o[2] + m[2, 3])
    d2 = (m[0, 0] * d[0] + m[0, 1] * d[1] + m[0, 2] * d[2],
          m[1, 0] * d[0] + m[1, 1] * d[1] + m[1, 2] * d[2],
          m[2, 0] * d[0] + m[2, 1] * d[1] + m[2, 2] * d[2])
    return o2, d2


@inlined
def grid_span(grids, g, o2, d2, t_max):
    """(s0, s1): the part of [0, ``t_max``] where the index-space ray ``o2`` + s ``d2`` lies inside grid
    ``g``'s bounds (the index box [-1, n] per axis, outside which the density is 0); s0 >= s1 if none."""
    s0, s1 = 0.0, t_max
    for axis in range(3):
        lo, hi = -1.0, float(grids.shape[g, axis])
        if d2[axis] == 0.0:
            if not (lo < o2[axis] < hi):
                return 1.0, 0.0
            continue
        a = (lo - o2[axis]) / d2[axis]
        b = (hi - o2[axis]) / d2[axis]
        if a > b:
            a, b = b, a
        s0 = max(s0, a)
        s1 = min(s1, b)
    return s0, s1


@inlined
def _voxel(grids, g, x, y, z):
    nx, ny, nz = grids.shape[g, 0], grids.shape[g, 1], grids.shape[g, 2]
    if x < 0 or y < 0 or z < 0 or x >= nx or y >= ny or z >= nz:
        return 0.0
    return float(grids.values[grids.offset[g] + (x * ny + y) * nz + z])


@kernel
def grid_density(grids, g, p):
    """The trilinear density of grid ``g`` at index-space point ``p`` (0 outside its voxels)."""
    fx, fy, fz = math.floor(p[0]), math.floor(p[1]), math.floor(p[2])
    tx, ty, tz = p[0] - fx, p[1] - fy, p[2] - fz
    x, y, z = int(fx), int(fy), int(fz)
    value = 0.0
    for corner in range(8):
        cx, cy, cz = corner & 1, (corner >> 1) & 1, (corner >> 2) & 1
        w = ((tx if cx else 1.0 - tx) * (ty if cy else 1.0 - ty) * (tz if cz else 1.0 - tz))
        if w > 0.0:
            value += w * _voxel(grids, g, x + cx, y + cy, z + cz)
    return value


@inlined
def density_along(grids, g, o2, d2, s):
    """The density at distance ``s`` along the index-space ray ``o2`` + s ``d2``."""
    return grid_density(grids, g, (o2[0] + s * d2[0], o2[1] + s * d2[1], o2[2] + s * d2[2]))
