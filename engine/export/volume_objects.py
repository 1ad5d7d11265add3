"""Blender Volume objects (OpenVDB) → a grid medium inside a null box, one per instance.

Cycles renders a Volume object with its first material's Volume shader, the Principled Volume's Density
multiplied by the float grid its Density Attribute names ("density" by default; a volume without a material
gets Cycles' default volume shader, a grey Principled Volume of Density 1 reading "density"). Prism reads
that grid from the object's OpenVDB file (the file of the current frame for sequences, as Blender resolves
it) and renders the material's medium (``nodes.volumes``) with σ_s and σ_a scaled by it, trilinearly
(``tracer.media.density_grid``), inside the box of the grid's voxels, a closed null surface placed with the
grid's transform and the object's matrix.

A Density driven by nodes (``nodes.volume_density``) runs on the grid's voxels at render time
(``tracer.media.voxel_inputs``), its Attribute nodes reading the object's grids of their names (0 where the
file has none, as in Cycles), and multiplies the Principled Volume's Density Attribute grid, as Cycles
multiplies the Density by it.

The Principled Volume's emission renders as Cycles': Emission Strength × Color and blackbody light, whose
temperature is the node's Temperature times the grid its Temperature Attribute names ("temperature" by
default; where the file has no such grid, the Temperature alone), read like the density grid and held in the
same medium (``tracer.media.temperature_emission``); the box then spans both grids.

Volume ▸ Render ▸ Space "Object" (Blender's default) makes the density follow the object's scale as in
Cycles 4.5 (``object_volume_density`` of its scene/object.cpp): every coefficient and the emission are
multiplied by 1 / |M (1, 1, 1) / √3|, M the instance's matrix, so a volume scaled up keeps its look instead
of thickening; "World" leaves them per world metre.

What cannot be read is warned, naming the object, what is missing and what renders instead: volumes whose
voxels come from Geometry Nodes or modifiers (bpy exposes no voxels, only files), packed files, grids that
are not float or not linear; the Color Attribute; light that fills the box where Cycles fills the active
voxels only (emission that does not vanish where the grids read 0).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..tracer.media.density_grid import DensityGrid
from ..tracer.media.spec import MediumSpec
from ..tracer.media import voxel_inputs
from ..tracer.media.voxel_inputs import VoxelInputs, resample, sample_axes
from ..tracer.scene import Material
from .mesh_data import LocalMesh
from .volume_emission import glow_note, index_box, socket_string, temperature_grid_name
from .volume_grids import GridUnreadable, float_grid_names, read_float_grid

#: Cycles' default volume shader (a Principled Volume with the node's defaults) for a volume without material.
DEFAULT_VOLUME = MediumSpec("Default volume", scatter=[(1.0, (0.5, 0.5, 0.5))],
                            absorb=[(1.0, (0.5, 0.5, 0.5), (0.0, 0.0, 0.0))])
DEFAULT_DENSITY_ATTRIBUTE = "density"

#: Cycles samples a grid's voxel i at the centre of index cell [i, i + 1] (half a voxel from OpenVDB's own
#: convention, values at integer indices, which the tracer follows): measured against Cycles 4.5 on the 16³
#: sphere of tests/blender/test_volume_objects.py (grey, Prism 1024 spp), this offset takes the RMS difference
#: of 4 × 4-pixel blocks from 1.5 % to 0.55 % (Cycles' own noise 0.5 %); -0.5 makes it 3.7 %.
CYCLES_VOXEL_OFFSET = 0.5

# The 12 triangles of the unit cube's faces, outward (corner c at x = c & 1, y = c >> 1 & 1, z = c >> 2 & 1).
_FACES = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
_BOX_TRIANGLES = np.array([[f[0], f[1], f[2]] for f in _FACES] + [[f[0], f[2], f[3]] for f in _FACES], np.int32)


def volume_shaders(material) -> list:
    """The Volume Absorption, Volume Scatter and Principled Volume nodes that feed ``material``'s Volume
    output (through Add and Mix Shaders and reroutes), as Cycles evaluates them."""
    tree = getattr(material, "node_tree", None)
    if tree is None or not material.use_nodes:
        return []
    output = tree.get_output_node("CYCLES")
    if output is None or "Volume" not in output.inputs:
        return []
    found, stack = [], [output.inputs["Volume"]]
    while stack:
        socket = stack.pop()
        for link in socket.links:
            if getattr(link, "is_muted", False):
                continue
            node = link.from_node
            if node.bl_idname == "NodeReroute":
                stack.append(node.inputs[0])
            elif node.bl_idname in ("ShaderNodeAddShader", "ShaderNodeMixShader"):
                stack.extend(s for s in node.inputs if s.type == "SHADER")
            elif node.bl_idname.startswith("ShaderNodeVolume"):
                found.append(node)
    return found


def _notes(name, material, nodes, grid) -> list[str]:
    """Warnings about what of the material's volume Prism renders otherwise than Cycles on this object."""
    notes = []
    label = f"material '{material.name}'" if material is not None else "Cycles' default volume shader"
    plain = [n.name for n in nodes if n.bl_idname != "ShaderNodeVolumePrincipled"]
    if grid is not None and plain:
        notes.append(f"Volume '{name}': {label} adds {', '.join(plain)} to the Principled Volume reading grid "
                     f"'{grid}'; Prism scales them by that grid too (Cycles fills the volume's active voxels "
                     "with them evenly).")
    for node in nodes:
        value = socket_string(node, "Color Attribute")
        if value:
            notes.append(f"Volume '{name}': {label}'s {node.name} reads grid '{value}' as its Color Attribute; "
                         "Prism does not read colour grids and renders the node's own Color throughout the volume.")
    return notes


def _density_grid_name(name, material, nodes, grids, notes) -> str | None:
    """The grid whose values scale the density (a Principled Volume's Density Attribute), or None."""
    wanted = [socket_string(n, "Density Attribute") for n in nodes if n.bl_idname == "ShaderNodeVolumePrincipled"]
    if material is None:
        wanted = [DEFAULT_DENSITY_ATTRIBUTE]
    wanted = [w for w in wanted if w]
    if len(set(wanted)) > 1:
        notes.append(f"Volume '{name}': its Principled Volumes read the density grids {sorted(set(wanted))}; "
                     f"Prism scales the whole volume by the first, '{wanted[0]}'.")
    if wanted and wanted[0] not in grids:
        notes.append(f"Volume '{name}': the density grid '{wanted[0]}' its material reads is not a float grid of "
                     f"its file (float grids: {grids or 'none'}); Cycles reads it as 0 there, and so Prism "
                     "renders nothing.")
        return ""
    return wanted[0] if wanted else None


def _box(low, high, index_to_object) -> LocalMesh:
    """The closed box from index corner ``low`` to ``high`` of a grid (its non-zero density: -1 .. n per axis,
    ``volume_emission.index_box``), in object space (outward)."""
    corners = np.array([[(c & 1), (c >> 1) & 1, (c >> 2) & 1] for c in range(8)], np.float64)
    corners = low + corners * (high - low)
    placed = corners @ index_to_object[:3, :3].T + index_to_object[:3, 3]
    triangles = _BOX_TRIANGLES if np.linalg.det(index_to_object[:3, :3]) > 0 else _BOX_TRIANGLES[:, ::-1].copy()
    a, b, c = (placed[triangles[:, k]] for k in range(3))
    normal = np.cross(b - a, c - a)
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    return LocalMesh(vertices=placed, triangles=triangles, slot_index=np.zeros(len(triangles), np.int32),
                     corner_normals=np.repeat(normal[:, None, :], 3, axis=1).astype(np.float32), slot_materials=[])


class VolumeReader:
    """Reads each Volume object's grid once per export; ``export_material(material)`` compiles a Blender
    material to (its index in the scene's materials, its tracer material) (``MaterialExporter.export``)."""

    def __init__(self, export_material):
        self.export_material = export_material
        self._read: dict = {}

    def _grid(self, obj, notes):
        """(path, float grid names, values, index_to_object, density grid name or None) or None (warned)."""
        import bpy

        volume = obj.data
        name = obj.name
        if any(modifier.show_render for modifier in getattr(obj.original, "modifiers", ())):
            notes.append(f"Volume '{name}' is not rendered: its modifiers or Geometry Nodes make its voxels, and "
                         "Blender's Python gives Prism no voxels but those of files; it renders as empty space.")
            return None
        original = volume.original if getattr(volume, "original", None) is not None else volume
        if not original.filepath:
            notes.append(f"Volume '{name}' is not rendered: it has no OpenVDB file (Blender's Python gives Prism "
                         "the voxels of files only); it renders as empty space.")
            return None
        if original.packed_file is not None:
            notes.append(f"Volume '{name}' is not rendered: its OpenVDB file is packed into the .blend, which "
                         "Prism cannot read; unpack it (File ▸ External Data ▸ Unpack Resources). It renders as "
                         "empty space.")
            return None
        path = bpy.path.abspath(volume.grids.frame_filepath or original.filepath, library=original.library)
        grids = float_grid_names(path)
        if not grids:
            notes.append(f"Volume '{name}' is not rendered: Prism can read no float grid of its OpenVDB file "
                         f"'{path}'; it renders as empty space.")
            return None
        return path, grids

    def read(self, obj, matrix_world, warnings=None) -> LocalMesh | None:
        """The box of ``obj``'s grid (object space), its slot material a tracer ``Material`` holding the grid
        medium placed by ``matrix_world`` (4x4), or None; what it cannot read is added to ``warnings`` (once)."""
        notes: list[str] = []
        box = self._read_box(obj, matrix_world, notes)
        if warnings is not None:
            warnings.extend(note for note in notes if note not in warnings)
        return box

    def _read_box(self, obj, matrix_world, notes):
        name = obj.name
        material = obj.material_slots[0].material if len(obj.material_slots) else None  # Cycles: the first slot
        nodes = volume_shaders(material) if material is not None else []
        key = (obj.original.name, obj.data.as_pointer(), material.name if material is not None else None)
        if key not in self._read:
            self._read[key] = self._load(obj, material, nodes, notes)
        loaded = self._read[key]
        if loaded is None:
            return None
        spec, values, index_to_object, grid, hot, inputs = loaded
        matrix = np.asarray(matrix_world, dtype=np.float64).reshape(4, 4)
        if getattr(getattr(obj.data, "render", None), "space", "OBJECT") == "OBJECT":
            spec = scaled_by(spec, object_space_density(matrix))
        if inputs is not None:  # what the nodes compute, baked on these voxels (× the Density Attribute grid)
            lattice = replace(inputs.lattice, index_to_world=matrix @ inputs.lattice.index_to_world,
                              name=f"{inputs.lattice.name} of '{name}'")
            spec = replace(spec, name=f"{spec.name} ({name})", density_grid=lattice,
                           voxel_inputs=replace(inputs, lattice=lattice))
        elif grid is not None:
            spec = replace(spec, name=f"{spec.name} ({name})",
                           density_grid=DensityGrid(values, matrix @ index_to_object, f"'{grid}' of '{name}'"))
        if hot is not None:
            spec = replace(spec, temperature_grid=DensityGrid(hot[0], matrix @ hot[1], f"'{hot[2]}' of '{name}'"))
        medium = Material(name=spec.name, kind="null", medium=spec)
        others = [(hot[0].shape, hot[1])] if hot is not None else []
        box = _box(*index_box(values.shape, index_to_object, others), index_to_object)
        box.slot_materials = [medium]
        return box

    def _load(self, obj, material, nodes, notes):
        name = obj.name
        found = self._grid(obj, notes)
        if found is None:
            return None
        path, grids = found
        source, spec = None, DEFAULT_VOLUME
        if material is not None:
            source, exported = self.export_material(material)
            spec = exported.medium
        if spec is None:
            notes.append(f"Volume '{name}': its material '{material.name}' has no volume shader on its Volume "
                         "output; it renders as empty space, as in Cycles.")
            return None
        grid = _density_grid_name(name, material, nodes, grids, notes)
        if grid == "":
            return None
        notes.extend(_notes(name, material, nodes, grid))
        lattice = grid if grid is not None else _lattice_name(spec, grids)
        if grid is None and lattice not in spec.density_attributes:  # a density of that grid is 0 where it is
            filled = "with the density its nodes compute" if spec.density_varies else "evenly"
            notes.append(f"Volume '{name}': its material reads no density grid (no Principled Volume Density "
                         f"Attribute or Attribute node); Prism fills the box of grid '{lattice}' {filled} (Cycles "
                         "fills its active voxels).")
        try:
            read = read_float_grid(path, lattice)
        except GridUnreadable as error:
            notes.append(f"Volume '{name}' is not rendered: {error}; it renders as empty space.")
            return None
        if read is None:
            return None  # no active voxel: nothing to see, as in Cycles
        values, index_to_object = read
        hot = self._temperature(name, nodes, path, grids, notes) if grid is not None else None
        if grid is None and temperature_grid_name(name, nodes, grids, []) is not None:
            notes.append(f"Volume '{name}': its material reads a temperature grid but no density grid; Prism "
                         "fills the box evenly at the Temperature set (Cycles multiplies it by the grid).")
        if hot is not None and spec.emission_field:
            notes.append(f"Volume '{name}': its material drives both the blackbody Temperature by grid '{hot[2]}' "
                         "and the Emission Strength by nodes; Prism follows one grid's light per volume, the "
                         "temperature's, and leaves the Emission Strength × Color light out.")
            spec = replace(spec, emission_field=[])
        if hot is not None:
            spec = replace(spec, temperature_grid=DensityGrid(hot[0], hot[1]))
        if grid is not None:
            note = glow_note(name, spec, values)
            notes.extend([note] if note else [])
        index_to_object = index_to_object @ _cycles_offset()
        inputs = None
        if spec.varies:  # in object space; ``_read_box`` places it per instance
            notes.extend(_subsampled_note(name, lattice, values.shape))
            inputs = VoxelInputs(source, DensityGrid(values if grid is not None else np.ones_like(values),
                                                     index_to_object, f"'{lattice}'"),
                                 _attribute_grids(name, spec, path, grids, values.shape, index_to_object, notes))
        return spec, values, index_to_object, grid, hot, inputs

    @staticmethod
    def _temperature(name, nodes, path, grids, notes):
        """(values, index_to_object, grid name) of the grid the material's blackbody reads as its temperature,
        or None (none: the Temperature alone, as Cycles renders it)."""
        hot = temperature_grid_name(name, nodes, grids, notes)
        if hot is None:
            return None
        try:
            read = read_float_grid(path, hot)
        except GridUnreadable as error:
            notes.append(f"Volume '{name}': {error}; Prism renders its blackbody light at the Temperature set, "
                         "throughout the volume.")
            return None
        if read is None:  # no active voxel: nothing to place; the Temperature alone
            return None
        return read[0], read[1] @ _cycles_offset(), hot


def _subsampled_note(name, lattice, shape) -> list[str]:
    """The warning for a lattice too large to run the material's program on every voxel (``sample_axes``)."""
    axes = sample_axes(shape)
    if [len(axis) for axis in axes] == list(shape):
        return []
    stride = int(max(axis[1] - axis[0] for axis in axes if len(axis) > 1))
    samples = int(np.prod([len(axis) for axis in axes]))
    return [f"Volume '{name}': grid '{lattice}' has {int(np.prod(shape)):,} voxels; Prism runs its material's nodes "
            f"on one voxel in {stride} along each axis ({samples:,} voxels: it bakes at most "
            f"{voxel_inputs.MAX_BAKED_VOXELS:,} per volume) and interpolates between them (Cycles runs them at "
            "every step); the grid's own values keep every voxel."]


def _lattice_name(spec, grids) -> str:
    """The grid whose voxels hold a Volume object's density where no Density Attribute names one: the first
    grid the density's nodes read, else the file's first float grid."""
    read = [name for name in {**spec.density_attributes, **spec.emission_attributes} if name in grids]
    return read[0] if read else grids[0]


def _attribute_grids(name, spec, path, grids, shape, lattice_to_object, notes) -> dict:
    """{colour slot: float32 ``shape``}: the grid each Attribute node of ``spec``'s density or emission names,
    resampled onto the lattice (index → object ``lattice_to_object``); zeros where the file has no such float
    grid (as Cycles reads a missing attribute), warned."""
    attributes = {}
    for attribute, slot in {**spec.density_attributes, **spec.emission_attributes}.items():
        attributes[slot] = np.zeros(shape, np.float32)
        if attribute not in grids:
            notes.append(f"Volume '{name}': its material reads the attribute '{attribute}', which is not a float grid "
                         f"of its file (float grids: {grids}); Cycles reads it as 0, and so does Prism.")
            continue
        try:
            read = read_float_grid(path, attribute)
        except GridUnreadable as error:
            notes.append(f"Volume '{name}': {error}; Prism reads the attribute '{attribute}' as 0.")
            continue
        if read is not None:
            attributes[slot] = resample(read[0], read[1] @ _cycles_offset(), lattice_to_object, shape)
    return attributes


def object_space_density(matrix) -> float:
    """Cycles' factor on a Volume object's density and emission in Object space: 1 / |M (1, 1, 1) / √3| for
    the object's 4x4 ``matrix`` (1 for any rotation, 1 / s for a uniform scale s)."""
    unit = np.full(3, 1.0 / np.sqrt(3.0))
    return float(1.0 / np.linalg.norm(np.asarray(matrix, dtype=np.float64)[:3, :3] @ unit))


def scaled_by(spec, factor):
    """``spec`` with its coefficients and emission multiplied by ``factor`` (the same spec when it is 1)."""
    if factor == 1.0:
        return spec
    return replace(spec, scatter=[(d * factor, *rest) for d, *rest in spec.scatter],
                   absorb=[(d * factor, *rest) for d, *rest in spec.absorb],
                   emission=[(s * factor, *rest) for s, *rest in spec.emission],
                   emission_field=[(s * factor, rgb) for s, rgb in spec.emission_field],
                   blackbody=[(w * factor, *rest) for w, *rest in spec.blackbody])


def _cycles_offset() -> np.ndarray:
    """Index → index shift by ``CYCLES_VOXEL_OFFSET`` (each voxel at the centre of its cell, as Cycles)."""
    offset = np.eye(4)
    offset[:3, 3] = CYCLES_VOXEL_OFFSET
    return offset
