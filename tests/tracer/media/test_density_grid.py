"""``density_grid.build_grids``: instances of one Volume object (grids holding the same voxel array, each its
own transform) share one copy of the voxels, and each reads its density where its own transform puts it."""

import numpy as np

from engine.tracer.jit import kernel
from engine.tracer.media.density_grid import DensityGrid, build_grids
from engine.tracer.media.grid_lookup import density_along, index_ray


@kernel
def _density_at(grids, g, points, out):
    for i in range(points.shape[0]):
        o2, d2 = index_ray(grids, g, (points[i, 0], points[i, 1], points[i, 2]), (1.0, 0.0, 0.0))
        out[i] = density_along(grids, g, o2, d2, 0.0)


def _placed(values, x):
    """``values`` with voxels of 0.1 m, shifted by ``x`` m along x."""
    matrix = np.diag([0.1, 0.1, 0.1, 1.0])
    matrix[0, 3] = x
    return DensityGrid(values, matrix)


def test_instances_of_one_grid_share_its_voxels_and_keep_their_places():
    rng = np.random.default_rng(5)
    smoke, other = rng.random((6, 5, 4)).astype(np.float32), 2.0 * rng.random((3, 3, 3)).astype(np.float32)
    grids = build_grids([_placed(smoke, 0.0), _placed(other, 0.0), _placed(smoke, 2.0)])
    assert grids.values.size == smoke.size + other.size  # the smoke's voxels once, not twice
    assert grids.offset.tolist() == [0, smoke.size, 0]
    assert grids.shape.tolist() == [[6, 5, 4], [3, 3, 3], [6, 5, 4]]
    assert grids.majorant.tolist() == [float(smoke.max()), float(other.max()), float(smoke.max())]
    points = rng.uniform((0.0, 0.0, 0.0), (0.5, 0.4, 0.3), size=(64, 3))
    first, second, empty = np.empty(64), np.empty(64), np.empty(64)
    _density_at(grids, 0, points, first)
    _density_at(grids, 2, points + (2.0, 0.0, 0.0), second)
    _density_at(grids, 2, points, empty)  # where the first instance is, the second has no voxels
    assert first.min() > 0.0 and np.allclose(first, second, rtol=1e-9, atol=0.0)  # up to rounding the shift
    assert np.all(empty == 0.0)
