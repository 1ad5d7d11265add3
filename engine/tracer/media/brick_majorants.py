"""Per-brick majorants of a density grid: the largest density each block of ``BRICK_VOXELS``³ voxels can take,
and a ray's walk from block to block, so that delta and ratio tracking draw tentative collisions at the rate of
the block they cross instead of the whole grid's largest density.

A smoke simulation is mostly empty air around a dense plume; with one majorant for the whole grid every metre
of that air costs as many tentative (null) collisions as the densest voxel. With a majorant per block, empty
blocks cost nothing (no collision, no random number) and thin ones few, as pbrt-v4's ``MajorantGrid`` and
Cycles' per-octree-node bounds do. Each block's bound is exact for trilinear interpolation: block b along an
axis covers index coordinates [bB − 1, (b + 1)B − 1) and a point there interpolates the voxels bB − 1 … (b + 1)B
− 1, whose largest value is the block's majorant (B = ``BRICK_VOXELS``; voxels outside the grid read 0). The
blocks tile the grid's bounds, the index box [−1, n], from −1 on; blocks outside the grid have majorant 0.

Along a ray o' + s d' (index space, ``grid_lookup``) the blocks are visited in order by a 3-D DDA (Amanatides
& Woo 1987, "A fast voxel traversal algorithm for ray tracing"): ``brick_entry`` gives the block at a point
and the distances s to its next boundary on each axis, ``brick_advance`` steps into the next block. With a
piecewise-constant majorant the free-flight optical depth −ln(1 − u) is spent block by block (the exponential
distribution is memoryless), so one random number still gives one tentative collision.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import inlined, kernel

#: Voxels per block edge. 8 keeps the block table 1/512 of the grid and its walk a few dozen steps across a
#: 256³ grid, while a plume's edge or a thin wisp still gets a bound of its own.
BRICK_VOXELS = 8


def brick_count(size: int, brick_voxels: int = BRICK_VOXELS) -> int:
    """Blocks along an axis of ``size`` voxels: enough to cover the index range [-1, size]."""
    return -(-(size + 1) // brick_voxels)


def _axis_maxima(values: np.ndarray, axis: int, brick_voxels: int) -> np.ndarray:
    """``values`` reduced along ``axis`` to each block's largest value over its voxels bB-1 .. (b+1)B-1."""
    size = values.shape[axis]
    count = brick_count(size, brick_voxels)
    starts = np.maximum(np.arange(count) * brick_voxels - 1, 0)  # every start lies inside the grid
    reduced = np.maximum.reduceat(values, starts, axis=axis)  # voxels start .. next start - 1
    ends = np.arange(1, count + 1) * brick_voxels - 1  # the voxel a block shares with the next one
    inside = np.flatnonzero(ends < size)
    if len(inside):
        index = [slice(None)] * values.ndim
        index[axis] = inside
        reduced[tuple(index)] = np.maximum(reduced[tuple(index)], np.take(values, ends[inside], axis=axis))
    return reduced


def brick_maxima(values: np.ndarray, brick_voxels: int = BRICK_VOXELS) -> np.ndarray:
    """float32 [bx, by, bz]: the majorant of every block of a grid of ``values`` [nx, ny, nz] (>= 0)."""
    reduced = np.asarray(values, np.float32)
    for axis in range(3):
        reduced = _axis_maxima(reduced, axis, brick_voxels)
    return np.ascontiguousarray(reduced, np.float32)


@kernel
def _axis_entry(grids, g, axis, x, direction):
    """(block, distance to its next boundary, distance between boundaries, step) along one axis from index
    coordinate ``x`` moving at ``direction`` index units per metre."""
    size = float(grids.brick_voxels[g])
    block = int(math.floor((x + 1.0) / size))
    if direction > 0.0:
        return block, ((block + 1) * size - 1.0 - x) / direction, size / direction, 1
    if direction < 0.0:
        return block, (block * size - 1.0 - x) / direction, -size / direction, -1
    return block, math.inf, math.inf, 0


@inlined
def brick_entry(grids, g, o2, d2, s):
    """(block (i, j, k), distance s of its next boundary per axis, distance between boundaries per axis, step
    per axis) of grid ``g`` where the index-space ray ``o2`` + s ``d2`` stands at ``s``."""
    x0, t0, w0, e0 = _axis_entry(grids, g, 0, o2[0] + s * d2[0], d2[0])
    x1, t1, w1, e1 = _axis_entry(grids, g, 1, o2[1] + s * d2[1], d2[1])
    x2, t2, w2, e2 = _axis_entry(grids, g, 2, o2[2] + s * d2[2], d2[2])
    return (x0, x1, x2), (s + t0, s + t1, s + t2), (w0, w1, w2), (e0, e1, e2)


@inlined
def brick_advance(block, following, width, step):
    """(block, next boundaries) after crossing the nearest boundary of ``following`` into the next block."""
    if following[0] <= following[1] and following[0] <= following[2]:
        return (block[0] + step[0], block[1], block[2]), (following[0] + width[0], following[1], following[2])
    if following[1] <= following[2]:
        return (block[0], block[1] + step[1], block[2]), (following[0], following[1] + width[1], following[2])
    return (block[0], block[1], block[2] + step[2]), (following[0], following[1], following[2] + width[2])


@inlined
def brick_majorant(grids, g, block):
    """The largest density grid ``g`` takes in ``block`` (0 outside its blocks)."""
    bx, by, bz = grids.brick_shape[g, 0], grids.brick_shape[g, 1], grids.brick_shape[g, 2]
    i, j, k = block
    if i < 0 or j < 0 or k < 0 or i >= bx or j >= by or k >= bz:
        return 0.0
    return float(grids.bricks[grids.brick_offset[g] + (i * by + j) * bz + k])
