"""A voxel grid of density that scales a medium's coefficients (an OpenVDB grid, a Blender Volume object's
"density"): ``DensityGrid`` as the export layer hands it over, and ``GridArrays``, the render's grids as the
kernels read them (``grid_lookup``).

Values sit at integer index coordinates (voxel centres, as OpenVDB stores them) and are interpolated
trilinearly; outside the array the density is 0 (OpenVDB's background), so the grid's density is non-zero
only inside the index box [-1, n] of each axis, its *bounds*. ``index_to_world`` is an affine map (any
rotation, scale or shear: OpenVDB's transform times the object's), the kernels use its inverse.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from ..errors import PrismInputError
from . import brick_majorants
from .brick_majorants import brick_maxima


@dataclass
class DensityGrid:
    """``values`` float32 [nx, ny, nz] (index x, y, z; unitless density, a factor of the medium's
    coefficients), ``index_to_world`` float64 [4, 4]: index coordinates (voxel centres at integers) to world
    metres. ``name`` for messages (the object and grid it came from)."""

    values: np.ndarray
    index_to_world: np.ndarray
    name: str = "density"


#: The grids of a render. ``values`` float32 (every grid's voxels, C order, one after another), per grid
#: ``offset`` int64 [G] (its first voxel in ``values``), ``shape`` int64 [G, 3], ``world_to_index`` float64
#: [G, 3, 4] (from positions relative to the render's origin, as the kernels' rays are), ``majorant``
#: float64 [G] (the largest density; trilinear interpolation never exceeds it); the per-block majorants that
#: bound delta and ratio tracking (``brick_majorants``): ``bricks`` float32 (every grid's blocks, C order),
#: ``brick_offset`` int64 [G], ``brick_shape`` int64 [G, 3] and ``brick_voxels`` int64 [G] (a block's edge).
GridArrays = namedtuple("GridArrays", "values offset shape world_to_index majorant bricks brick_offset brick_shape "
                        "brick_voxels")

#: The most tentative collisions delta or ratio tracking takes along one ray segment. A walk takes about
#: μ L of them (the majorant's optical depth across the segment), so a realistic medium stays far below;
#: the bound keeps an absurd density (a multiplier of 1e20, where free flights fall below the resolution of
#: a float64 distance and the walk would stand still) from hanging the render. A walk that reaches it
#: counts as opaque: transmittance 0, the path ends.
MAX_TRACKING_STEPS = 1 << 20


def check_grid(grid: DensityGrid, medium_name: str) -> None:
    """Raise a ``PrismInputError`` naming the medium for a grid that cannot be rendered."""
    values = np.asarray(grid.values)
    if values.ndim != 3 or min(values.shape) < 1:
        raise PrismInputError(f"Volume '{medium_name}': its {grid.name} grid is not a 3-D array of voxels.")
    if not np.all(np.isfinite(values)):
        raise PrismInputError(f"Volume '{medium_name}': its {grid.name} grid holds NaN or infinite values.")
    matrix = np.asarray(grid.index_to_world, dtype=np.float64)
    if matrix.shape != (4, 4) or not np.all(np.isfinite(matrix)) or abs(np.linalg.det(matrix[:3, :3])) < 1e-300:
        raise PrismInputError(f"Volume '{medium_name}': the transform of its {grid.name} grid is not invertible "
                              "(an object scaled to 0?).")


def build_grids(grids, origin=None, brick_voxels: int | None = None) -> GridArrays:
    """``GridArrays`` for a list of ``DensityGrid`` (negative densities clamped to 0: a medium's
    coefficients are never negative); ``origin`` (m, [3]) the point the kernels' positions are relative
    to. Grids that hold the same ``values`` array (instances of one Volume object) share its voxels and
    blocks: one copy, each grid its own transform. ``brick_voxels``: the blocks' edge (default
    ``brick_majorants.BRICK_VOXELS``, read when called; a size past every grid's gives one block, the whole
    grid's majorant, as before blocks)."""
    if brick_voxels is None:
        brick_voxels = brick_majorants.BRICK_VOXELS
    count = max(len(grids), 1)
    offset = np.zeros(count, np.int64)
    shape = np.ones((count, 3), np.int64)
    world_to_index = np.zeros((count, 3, 4))
    majorant = np.zeros(count)
    brick_offset = np.zeros(count, np.int64)
    brick_shape = np.ones((count, 3), np.int64)
    block_chunks, first_block = [], 0
    chunks, first, stored = [], 0, {}  # stored: id of a grid's values → (offset, majorant, blocks, their shape)
    shift = np.zeros(3) if origin is None else np.asarray(origin, dtype=np.float64)
    for g, grid in enumerate(grids):
        inverse = np.linalg.inv(np.asarray(grid.index_to_world, dtype=np.float64))
        # index = A (p + origin) + b for a position p relative to the origin
        world_to_index[g, :, :3] = inverse[:3, :3]
        world_to_index[g, :, 3] = inverse[:3, :3] @ shift + inverse[:3, 3]
        shape[g] = np.shape(grid.values)
        if id(grid.values) not in stored:  # ``grids`` holds every values array, so no id is reused meanwhile
            values = np.maximum(np.ascontiguousarray(grid.values, dtype=np.float32), 0.0)
            blocks = brick_maxima(values, brick_voxels)
            stored[id(grid.values)] = first, float(values.max()), first_block, blocks.shape
            chunks.append(values.ravel())
            block_chunks.append(blocks.ravel())
            first += values.size
            first_block += blocks.size
        offset[g], majorant[g], brick_offset[g], brick_shape[g] = stored[id(grid.values)]
    values = np.concatenate(chunks) if chunks else np.zeros(1, np.float32)
    bricks = np.concatenate(block_chunks) if block_chunks else np.zeros(1, np.float32)
    return GridArrays(values, offset, shape, world_to_index, majorant, bricks, brick_offset, brick_shape,
                      np.full(count, brick_voxels, np.int64))
