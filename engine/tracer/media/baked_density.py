"""A volume's varying Density (a Noise Texture, a gradient: ``export.nodes.volume_density``) baked onto a voxel
grid over the meshes that hold it, so that the medium renders as a grid medium (delta and ratio tracking,
trilinear between voxel centres: ``density_grid``).

Cycles 4.5 ray-marches such a volume, evaluating the shader once per step of 1/10 of the mean edge of the
object's bounds times Material ▸ Settings ▸ Volume ▸ Step Rate (``Object::compute_volume_step_size``). The
grid's voxels are ``BAKED_VOXELS_PER_STEP`` times finer than that step (so a smaller Step Rate gives a finer
grid, as it gives Cycles finer steps), across the bounds of every object with the material, their centres on
the bounds' faces; at most ``MAX_BAKED_VOXELS`` voxels (the voxels grow evenly past it).

A Principled Volume's Emission Strength driven by nodes is baked the same way, onto the same voxels
(``BakedFields``), and the medium's emission follows it (``temperature_emission.emission_rows``).

The program runs at the voxel centres as at the corners of triangles: three centres make one probe
triangle, and the kernel that evaluates true displacement at triangle corners (``materials.displacement``)
evaluates the density there, so no kernel is compiled for baking. The probe triangles have no corner data
(UV maps, colour attributes read as missing, as inside a Cycles volume) and belong to the object whose bounds
hold the centre: Generated and Object coordinates and Object Info are that object's. A density that reads
the surface or the ray is not baked (the export renders it at the socket's value).

A Volume object's density is baked on its own voxels instead (``bake_on_voxels``, ``voxel_inputs``): the
probe triangles' corners are its voxel centres and carry its grids as the colour attributes the material's
Attribute nodes read. Past ``MAX_BAKED_VOXELS`` the program runs on every few voxels and its result is
interpolated between them, while the Density Attribute grid it multiplies keeps every voxel.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..bsdf.closure import CLOSURE_ROW, MAX_CLOSURES
from ..materials.displacement import corner_displacements
from ..materials.light_path import FIELDS
from .density_grid import DensityGrid
from .voxel_inputs import MAX_BAKED_VOXELS, sample_axes, upsample

#: Cycles' ray-marching step for a volume without voxel grids, as a fraction of the mean edge of its bounds.
CYCLES_STEP_FRACTION = 0.1
#: Voxels per Cycles step: fine enough that trilinear interpolation follows what Cycles' steps resolve.
BAKED_VOXELS_PER_STEP = 8.0
#: Voxel centres evaluated per kernel call (bounds the scratch arrays).
_POINTS_PER_CALL = 1 << 18


def _instance_rows(geometry, triangles):
    """The object row of each of ``triangles`` (-1 where no object data is exported)."""
    instance = geometry.attributes.instance
    return instance[triangles] if len(instance) >= geometry.triangles.shape[0] else np.full(len(triangles), -1)


def _object_bounds(geometry, triangles):
    """{instance row: (low, high)} of the vertices of ``triangles`` (positions relative to the origin)."""
    rows = _instance_rows(geometry, triangles)
    bounds = {}
    for row in np.unique(rows):
        corners = geometry.vertices[geometry.triangles[triangles[rows == row]].ravel()].astype(np.float64)
        bounds[int(row)] = (corners.min(axis=0), corners.max(axis=0))
    return bounds


def grid_layout(bounds, step_rate):
    """(low corner, voxel spacing [3], voxel counts [3]) of the grid over ``bounds`` ({row: (low, high)})."""
    steps = [CYCLES_STEP_FRACTION * float(np.mean(high - low)) * step_rate for low, high in bounds.values()]
    steps = [s for s in steps if s > 0.0]
    low = np.min([lo for lo, _ in bounds.values()], axis=0)
    high = np.max([hi for _, hi in bounds.values()], axis=0)
    size = high - low
    voxel = min(steps) / BAKED_VOXELS_PER_STEP if steps else 1.0
    while True:
        counts = np.maximum(np.ceil(size / voxel).astype(np.int64) + 1, 1)
        if int(np.prod(counts)) <= MAX_BAKED_VOXELS:
            break
        voxel *= (float(np.prod(counts)) / MAX_BAKED_VOXELS) ** (1.0 / 3.0) * 1.01
    spacing = np.where(counts > 1, size / np.maximum(counts - 1, 1), voxel)
    return low, spacing, counts


def _probe(geometry, points, material, row, colours):
    """A ``Geometry`` whose triangles have ``points`` (float32 [3 P, 3]) as corners, all of ``material`` and
    instance ``row``, with ``colours`` [slots, 3 P] as grey colour attributes (alpha 1, as Cycles reads a float
    grid) and no other corner data; the same array types as ``geometry``'s, so the kernel compiled for it runs."""
    count = len(points) // 3
    a = geometry.attributes

    def empty(array, axes=(0,)):
        return np.zeros([0 if axis in axes else n for axis, n in enumerate(array.shape)], array.dtype)

    corner_colours = np.ones((len(colours), count, 3, 4), a.colors.dtype)
    corner_colours[..., :3] = np.reshape(colours, (len(colours), count, 3, 1))
    attributes = a._replace(uvs=empty(a.uvs, (1,)), colors=corner_colours, tangents=empty(a.tangents, (1,)),
                            positions=empty(a.positions), instance=np.full(count, row, a.instance.dtype))
    return geometry._replace(
        vertices=np.ascontiguousarray(points, dtype=geometry.vertices.dtype),
        triangles=np.arange(3 * count, dtype=geometry.triangles.dtype).reshape(count, 3),
        material=np.full(count, material, geometry.material.dtype), normals=empty(geometry.normals),
        attributes=attributes, flags=np.zeros(count, geometry.flags.dtype), motion=empty(geometry.motion, (0, 1)),
        motion_normals=empty(geometry.motion_normals, (0, 1)), spheres=empty(geometry.spheres),
        sphere_random=empty(geometry.sphere_random), curves=empty(geometry.curves),
        curve_segments=empty(geometry.curve_segments), curve_info=empty(geometry.curve_info),
        sphere_motion=empty(geometry.sphere_motion, (0, 1)), terminator=empty(geometry.terminator))


def _evaluate(geometry, arrays, registers, register_count, material, row, points, colours=None):
    """The value ``material``'s program computes in ``registers`` at ``points`` (float64 [P, 3], relative to
    the origin), where its colour attributes read ``colours`` [slots, P] (None: none)."""
    pad = (-len(points)) % 3
    padded = np.concatenate([points, np.repeat(points[-1:], pad, axis=0)])
    colours = np.zeros((0, len(points))) if colours is None else np.asarray(colours)
    colours = np.concatenate([colours, np.repeat(colours[:, -1:], pad, axis=1)], axis=1)
    probe = _probe(geometry, padded.astype(np.float32), material, row, colours)
    out = np.zeros((len(padded) // 3, 3, 3))
    regs = np.zeros(max(int(register_count), 1) + FIELDS)
    corner_displacements(probe, arrays, registers, np.zeros((MAX_CLOSURES, CLOSURE_ROW)), regs, out)
    return out[:, :, 0].ravel()[:len(points)]


def bake_density(geometry, arrays, registers, register_count, material, spec, origin) -> DensityGrid | None:
    """The ``DensityGrid`` (world metres) of what ``material``'s program computes in ``registers`` (its varying
    density, or Emission Strength) over the objects that hold it, or None when no triangle has the material."""
    on = np.flatnonzero(geometry.material[:geometry.triangles.shape[0]] == material)
    if not len(on):
        return None
    bounds = _object_bounds(geometry, on)
    low, spacing, counts = grid_layout(bounds, spec.step_rate)
    values = np.zeros(counts, np.float32)
    per_slab = max(1, _POINTS_PER_CALL // int(counts[1] * counts[2]))
    j, k = np.meshgrid(np.arange(counts[1]), np.arange(counts[2]), indexing="ij")
    for first in range(0, int(counts[0]), per_slab):
        i = np.arange(first, min(first + per_slab, int(counts[0])))
        index = np.stack(np.broadcast_arrays(i[:, None, None], j[None], k[None]), axis=-1).reshape(-1, 3)
        centres = low + index * spacing
        owner = np.full(len(centres), -2)
        for row, (lo, hi) in bounds.items():  # a voxel next to an object's bounds still shades its inside
            inside = np.all((centres >= lo - spacing) & (centres <= hi + spacing), axis=1) & (owner == -2)
            owner[inside] = row
        slab = np.zeros(len(centres))
        for row in bounds:
            mine = owner == row
            if mine.any():
                slab[mine] = _evaluate(geometry, arrays, registers, register_count, material, row, centres[mine])
        values[i[0]:i[-1] + 1] = np.where(np.isfinite(slab), slab, 0.0).reshape(len(i), counts[1], counts[2])
    index_to_world = np.diag([*spacing, 1.0])
    index_to_world[:3, 3] = low + (np.zeros(3) if origin is None else np.asarray(origin, dtype=np.float64))
    return DensityGrid(values, index_to_world, f"density baked from material '{spec.name}'")


def bake_on_voxels(geometry, arrays, registers, register_count, inputs, row, origin, scaled) -> DensityGrid:
    """The ``DensityGrid`` of what a Volume object's material computes in ``registers`` (``inputs``, a
    ``voxel_inputs.VoxelInputs``): the program of material ``inputs.source`` at each voxel of ``inputs.lattice``,
    with its grids as attributes and object row ``row``, times the lattice's own values where ``scaled`` (the
    density, as Cycles multiplies it by the Density Attribute grid; not the emission)."""
    lattice = inputs.lattice
    shape = lattice.values.shape
    axes = sample_axes(shape)
    samples = np.zeros([len(axis) for axis in axes], np.float32)
    slots = max(inputs.attributes, default=-1) + 1
    matrix = np.asarray(lattice.index_to_world, dtype=np.float64)
    shift = matrix[:3, 3] - (np.zeros(3) if origin is None else np.asarray(origin, dtype=np.float64))
    per_slab = max(1, _POINTS_PER_CALL // int(samples.shape[1] * samples.shape[2]))
    jk = np.stack(np.meshgrid(axes[1], axes[2], indexing="ij"), axis=-1).reshape(-1, 2)
    for first in range(0, samples.shape[0], per_slab):
        i = axes[0][first:first + per_slab]
        index = np.hstack([np.repeat(i, len(jk))[:, None], np.tile(jk, (len(i), 1))])
        colours = np.zeros((slots, len(index)))
        for slot, grid in inputs.attributes.items():
            colours[slot] = grid[np.ix_(i, axes[1], axes[2])].ravel()
        slab = _evaluate(geometry, arrays, registers, register_count, inputs.source, row,
                         index @ matrix[:3, :3].T + shift, colours)
        samples[first:first + len(i)] = np.where(np.isfinite(slab), slab, 0.0).reshape(len(i), *samples.shape[1:])
    values = upsample(samples, axes, shape)
    what = "density" if scaled else "emission strength"
    return DensityGrid(values * lattice.values if scaled else values, matrix,
                       f"{what} baked on the voxels of {lattice.name}")


#: A medium's baked grids: ``density`` and ``strength`` (its Emission Strength), each a ``DensityGrid`` or None.
BakedFields = namedtuple("BakedFields", "density strength")


def _bake(geometry, arrays, registers, register_count, materials, m, origin, density) -> DensityGrid | None:
    """Material ``m``'s field of ``registers`` (its density where ``density``, else its emission strength)."""
    spec = materials[m].medium
    inputs = spec.voxel_inputs
    if inputs is None:
        return bake_density(geometry, arrays, registers, register_count, m, spec, origin) if registers[m] >= 0 else None
    on = np.flatnonzero(geometry.material[:geometry.triangles.shape[0]] == m)
    if not len(on) or registers[inputs.source] < 0:
        return None
    row = int(_instance_rows(geometry, on[:1])[0])
    return bake_on_voxels(geometry, arrays, registers, register_count, inputs, row, origin, density)


def bake_fields(geometry, arrays, density, emission, register_count, materials, origin) -> dict:
    """{material index: ``BakedFields``} of the media whose density or Emission Strength a program computes
    per point (registers int32 [materials] ``density`` and ``emission``, -1: none), over the meshes that hold
    them, or on a Volume object's voxels (``MediumSpec.voxel_inputs``)."""
    baked = {}
    for m, material in enumerate(materials):
        spec = getattr(material, "medium", None)
        if spec is None or not spec.varies:
            continue
        fields = BakedFields(
            _bake(geometry, arrays, density, register_count, materials, m, origin, True) if spec.density_varies
            else None,
            _bake(geometry, arrays, emission, register_count, materials, m, origin, False) if spec.emission_field
            else None)
        if fields.density is not None or fields.strength is not None:
            baked[m] = fields
    return baked
