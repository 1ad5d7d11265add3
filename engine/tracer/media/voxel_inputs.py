"""What a Volume object's node-driven Density reads at each of its voxels: the lattice the material's program
runs on (a grid of the object's OpenVDB file, placed in the world) and the object's grids its Attribute nodes
name, resampled onto that lattice. The render bakes the density there (``baked_density.bake_on_voxels``), as
Cycles runs the volume shader with each grid sampled where it shades.

Baking runs the nodes at the voxel centres and interpolates their result trilinearly, where Cycles
interpolates the grids and runs the nodes at every step: the same for nodes linear in the grids (a Math
Multiply, Add), and within the variation across one voxel for others (a Color Ramp, a Power). A lattice of
more than ``MAX_BAKED_VOXELS`` voxels runs the program on every few voxels along each axis
(``sample_axes``) and interpolates its result between them (``upsample``); the grid it multiplies keeps every
voxel.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .density_grid import DensityGrid

#: The most voxels one volume's baked grid holds (64 MiB of float32), or a Volume object's program runs on.
MAX_BAKED_VOXELS = 1 << 24
#: Voxels resampled per call (bounds the index arrays scipy is handed: 3 float64 per voxel).
_VOXELS_PER_CALL = 1 << 21


@dataclass
class VoxelInputs:
    """``source``: the index (in the scene's materials) of the material whose program computes the density;
    ``lattice``: the voxels where it runs (``index_to_world``: their centres in world metres), whose ``values``
    multiply its result (a Principled Volume's Density Attribute grid, as Cycles multiplies the Density by it;
    ones where the material reads none); ``attributes``: {colour slot: float32 array of the lattice's shape},
    the grid each Attribute node of the density reads (zeros where the file has no grid of that name)."""

    source: int
    lattice: DensityGrid
    attributes: dict = field(default_factory=dict)


def resample(values, index_to_object, lattice_to_object, shape) -> np.ndarray:
    """float32 ``shape``: the grid ``values`` (index → object ``index_to_object``) at the voxel centres of a
    lattice of ``shape`` (index → object ``lattice_to_object``), trilinearly, 0 outside it (OpenVDB's
    background, as ``density_grid`` reads grids)."""
    from scipy.ndimage import map_coordinates

    to_source = np.linalg.solve(np.asarray(index_to_object, np.float64), np.asarray(lattice_to_object, np.float64))
    if values.shape == tuple(shape) and np.allclose(to_source, np.eye(4), atol=1e-9):
        return np.asarray(values, np.float32)
    out = np.zeros(shape, np.float32)
    per_slab = max(1, _VOXELS_PER_CALL // int(shape[1] * shape[2]))
    jk = np.indices(shape[1:]).reshape(2, -1).astype(np.float64)
    for first in range(0, int(shape[0]), per_slab):
        i = np.arange(first, min(first + per_slab, int(shape[0])), dtype=np.float64)
        ijk = np.vstack([np.repeat(i, jk.shape[1]), np.tile(jk, len(i))])
        where = to_source[:3, :3] @ ijk + to_source[:3, 3:4]
        out[first:first + len(i)] = map_coordinates(np.asarray(values, np.float32), where, order=1,
                                                    mode="grid-constant", cval=0.0).reshape(len(i), *shape[1:])
    return out


def sample_axes(shape) -> list:
    """The voxel indices along each axis of a lattice of ``shape`` where its program runs: every voxel while
    the lattice holds at most ``MAX_BAKED_VOXELS``, else every ``stride``-th one and the last, the smallest
    stride that keeps the samples within it (the program's result is interpolated between them: ``upsample``)."""
    most = MAX_BAKED_VOXELS
    stride = 1
    while int(np.prod([-(-(n - 1) // stride) + 1 for n in shape])) > most:
        stride += 1
    return [np.unique(np.minimum(np.arange(0, n - 1 + stride, stride), n - 1)) for n in shape]


def upsample(samples, axes, shape) -> np.ndarray:
    """float32 ``shape``: ``samples`` (the values at the voxels ``axes`` pick, ``sample_axes``) interpolated
    trilinearly onto every voxel."""
    from scipy.ndimage import map_coordinates

    if tuple(samples.shape) == tuple(shape):
        return np.asarray(samples, np.float32)
    # Each voxel's position among the samples, per axis (the last interval may be shorter than a stride).
    at = [np.interp(np.arange(n), axis, np.arange(len(axis))) for n, axis in zip(shape, axes)]
    samples = np.asarray(samples, np.float32)
    out = np.empty(shape, np.float32)
    per_slab = max(1, _VOXELS_PER_CALL // int(shape[1] * shape[2]))
    for first in range(0, int(shape[0]), per_slab):
        rows = at[0][first:first + per_slab]
        where = np.stack(np.broadcast_arrays(rows[:, None, None], at[1][None, :, None], at[2][None, None, :]))
        out[first:first + len(rows)] = map_coordinates(samples, where.reshape(3, -1), order=1,
                                                       mode="nearest").reshape(len(rows), *shape[1:])
    return out


def program_sources(materials, used) -> set:
    """The indices of the materials whose programs bake the densities of the Volume objects in ``used``."""
    sources = set()
    for m in used:
        inputs = getattr(getattr(materials[m], "medium", None), "voxel_inputs", None)
        if inputs is not None:
            sources.add(int(inputs.source))
    return sources
