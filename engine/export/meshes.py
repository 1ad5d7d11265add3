"""Evaluated geometry → one world-space triangle soup, each piece of geometry exported once.

Blender evaluates Text, Curve, Surface and Metaball objects to meshes and lists
each such mesh as an instance of its own in ``depsgraph.object_instances``; the
objects themselves are skipped here (as Cycles does), so their surfaces are not
exported twice. Hair Curves and particle hair (``particle_hair``) become round curves (``hair``);
point clouds become spheres (``point_clouds``); Volume objects a null box around a grid medium (``volume_objects``).

The instances of one mesh are gathered while iterating (the only Python work per
instance is reading its key and matrix) and placed in one numpy step per mesh
(``instancing``, which also states the memory an instance costs). Vertices stay
float64 world positions: the tracer subtracts the camera position before its
float32 geometry, so small objects far from the origin keep their shape.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..tracer.curves import CurveSegments, padded_strands
from ..tracer.scene import Material
from ..tracer.spheres import SpherePoints
from .hair import LocalHair, placed_strands, read_hair
from .instancing import WorldTriangles, instance_triangles
from .adaptive_subdivision import adaptive_subdivision_warning
from .bump_space import both_bump_scale_warning
from .cryptomatte_names import asset_name
from .materials import DEFAULT_MATERIAL
from .material_rows import MaterialRows
from .mesh_data import AttributeRequest, LocalMesh, read_mesh
from .object_random import name_random_id
from .particle_hair import hair_materials, read_particle_hair, uncarried_warning
from .point_clouds import LocalPoints, place_points, point_random, read_points
from .data_passes import data_pass_switches, world_ao_distance
from .surface_attributes import SurfaceCollector, stacked_slots
from .texture_memory import TextureBudget
from .unrendered import unrendered_type_warning
from .velocity import placed_velocity
from .volume_objects import VolumeReader
from .view_layer_filter import layer_filter
from .shadow_terminator import terminator_offsets
from .visibility import object_flags

#: Types whose evaluated mesh arrives as a separate MESH instance.
_EVALUATED_AS_MESH_INSTANCE = {"CURVE", "FONT", "SURFACE", "META"}


@dataclass
class ExportedGeometry:
    vertices: np.ndarray
    triangles: np.ndarray
    triangle_material: np.ndarray
    triangle_object: np.ndarray
    corner_normals: np.ndarray
    object_names: list[str]
    materials: list[Material]
    object_light_groups: list[str] = field(default_factory=list)
    surface: object = None  # scene.SurfaceAttributes read by node materials, or None
    object_flags: np.ndarray | None = None  # uint8 per entry of object_names (``tracer.visibility``)
    # What the data passes read (``data_passes``), None unless the view layer asks for the pass: Object ▸
    # Pass Index per triangle, the render UV map per triangle corner (u, v, 1; 0, 0, 0 on meshes without one);
    # Material ▸ Pass Index per material.
    triangle_pass_index: np.ndarray | None = None
    pass_uv: np.ndarray | None = None
    material_pass_index: tuple = ()
    points: SpherePoints | None = None  # the points of point clouds (objects numbered after the triangles')
    point_velocity: np.ndarray | None = None  # float64 [N, 3]: their velocity attribute (m/s, world; NaN: none)
    vertex_object: np.ndarray | None = None  # int32 [V]: each vertex's object (an index into object_names)
    vertex_velocity: np.ndarray | None = None  # float64 [V, 3]: the velocity attribute of meshes (as points')
    object_matrices: list = field(default_factory=list)  # per object: float64 [K, 4, 4], its instances' transforms
    curve_velocity: np.ndarray | None = None  # float64 [P, 3]: of the curves' control points (as points')
    curves: CurveSegments | None = None  # the strands of hair curves (objects numbered after the points')
    triangle_flat: np.ndarray | None = None  # bool [T]: the triangle's face is shaded flat
    # float32 [T, 2]: its object's Geometry Offset (0 where shaded flat) and Shading Offset multiplier (0: none)
    triangle_terminator: np.ndarray | None = None
    object_asset_names: list[str] = field(default_factory=list)  # per object_names entry (Cryptomatte Asset)
    material_names: list[str] = field(default_factory=list)  # per material, Cycles' name (Cryptomatte Material)


@dataclass
class _Instances:
    """One piece of evaluated geometry and where it is placed."""

    name: str
    geometry: LocalMesh | LocalHair | LocalPoints
    matrices: list = field(default_factory=list)  # 16 floats each, row-major
    infos: list = field(default_factory=list)  # (colour RGBA, pass index, random id) per instance
    light_group: str = ""  # Object ▸ Shading ▸ Light Group
    flags: int = 0
    asset: str = ""  # the name of the object's topmost parent (Cryptomatte Asset)
    terminator: tuple = (0.0, 0.0)  # Object ▸ Shading ▸ Shadow Terminator's offsets (``shadow_terminator``)


@dataclass
class _Objects:
    """The exported objects, one row per piece placed, in the order of ``ExportedGeometry.object_names``."""

    names: list = field(default_factory=list)
    assets: list = field(default_factory=list)
    groups: list = field(default_factory=list)
    flags: list = field(default_factory=list)
    matrices: list = field(default_factory=list)  # float64 [K, 4, 4] per object: its instances' transforms

    def add(self, piece: _Instances, matrices: np.ndarray) -> int:
        """Add ``piece`` placed at ``matrices``; its object index."""
        for table, value in ((self.names, piece.name), (self.assets, piece.asset), (self.groups, piece.light_group),
                             (self.flags, piece.flags), (self.matrices, matrices)):
            table.append(value)
        return len(self.names) - 1


def read_geometry(key: tuple, obj, request: AttributeRequest | None = None,
                  warn=None) -> LocalMesh | LocalHair | LocalPoints | None:
    """The evaluated geometry of ``obj`` (``key``: (type, original name, data pointer), the piece it is;
    ``PARTICLES`` keys add whether this is a render) with the per-corner data ``request`` names (meshes)."""
    if key[0] == "PARTICLES":
        return read_particle_hair(obj, key[3], request)
    if key[0] == "MESH":
        return read_mesh(obj, request, warn)
    return read_points(obj, request) if key[0] == "POINTCLOUD" else read_hair(obj, request)


def _gather(depsgraph, warnings, read, materials) -> list[_Instances]:
    """Every rendered piece of geometry with the matrices of its instances."""
    pieces: dict[tuple, _Instances | None] = {}
    warned: set[str] = set()
    included = layer_filter(getattr(depsgraph, "view_layer", None))  # View Layer ▸ Filter, as Cycles syncs it
    render = getattr(depsgraph, "mode", "RENDER") == "RENDER"  # particle hair: render or viewport steps
    volumes = VolumeReader(lambda m: (i := int(materials.slot_lookup([m])[0]), materials.materials[i]))

    def warn_once(obj, messages):
        name = obj.original.name
        if name not in warned:
            warned.add(name)
            if warnings is not None:
                warnings.extend(messages)

    for instance in depsgraph.object_instances:
        obj = instance.object
        kind = obj.type
        if kind == "MESH" and instance.show_particles and len(obj.particle_systems) and included.renders("CURVES"):
            key = ("PARTICLES", obj.original.name, obj.data.as_pointer(), render)
            if key not in pieces:
                request = materials.request(hair_materials(obj, render))
                hair = read(key, obj, request, lambda message, obj=obj: warn_once(obj, [message]))
                if hair is not None and hair.uncarried and warnings is not None:
                    warnings.append(uncarried_warning(obj.name, hair.uncarried))
                pieces[key] = (_Instances(obj.name, hair, light_group=obj.lightgroup,
                                          flags=object_flags(obj, getattr(depsgraph, "view_layer", None), warnings),
                                          asset=asset_name(obj), terminator=terminator_offsets(obj, "HAIR", warnings))
                               if hair is not None else None)
            _place(pieces[key], instance, obj)
        if not instance.show_self or kind in _EVALUATED_AS_MESH_INSTANCE or not included.renders(kind):
            continue
        if kind == "VOLUME":  # a piece per instance: its grid medium is placed by the instance's matrix
            box = volumes.read(obj, instance.matrix_world, warnings)
            if box is not None:
                piece = _Instances(obj.name, box, light_group=obj.lightgroup, asset=asset_name(obj),
                                   flags=object_flags(obj, getattr(depsgraph, "view_layer", None), warnings))
                pieces[("VOLUME", len(pieces))] = piece
                _place(piece, instance, obj)
            continue
        if kind not in ("MESH", "CURVES", "POINTCLOUD"):
            message = unrendered_type_warning(obj)
            if message:
                warn_once(obj, [message])
            continue
        key = (kind, obj.original.name, obj.data.as_pointer())
        if key not in pieces:
            request = materials.request([slot.material for slot in obj.material_slots])
            # read now: the object may be temporary
            geometry = read(key, obj, request, lambda message, obj=obj: warn_once(obj, [message]))
            flags = object_flags(obj, getattr(depsgraph, "view_layer", None), warnings)
            for message in (adaptive_subdivision_warning(obj, depsgraph.scene),
                            both_bump_scale_warning(obj) if kind == "MESH" else None):
                if message is not None and warnings is not None:
                    warnings.append(message)
            pieces[key] = (_Instances(obj.name, geometry, light_group=obj.lightgroup, flags=flags,
                                      asset=asset_name(obj), terminator=terminator_offsets(obj, kind, warnings))
                           if geometry is not None else None)
        _place(pieces[key], instance, obj)
    return [piece for piece in pieces.values() if piece is not None]


def _place(piece: _Instances | None, instance, obj) -> None:
    """Add ``instance``'s transform and object info to ``piece`` (None: nothing to place)."""
    if piece is None:
        return
    matrix = instance.matrix_world
    piece.matrices.append((*matrix[0], *matrix[1], *matrix[2], *matrix[3]))
    random_id = instance.random_id if instance.is_instance else name_random_id(obj.name)
    piece.infos.append((tuple(obj.color), obj.pass_index, random_id))


def export_meshes(depsgraph, warnings: list[str] | None = None, read=read_geometry) -> ExportedGeometry:
    """Every visible mesh, hair and point cloud instance, in world space (metres, float64 vertices).

    Hair renders as round curves (``tracer.curves.CurveSegments``) whatever Render ▸ Curves ▸ Shape says
    (``hair``). ``read(key, obj)`` returns a piece's geometry (the viewport passes one that keeps what did not
    change). Material warnings and geometry Prism skips are appended to ``warnings``.
    """
    materials = MaterialRows(warnings, TextureBudget.for_scene(depsgraph.scene), world_ao_distance(depsgraph.scene))
    parts: list[tuple[WorldTriangles, np.ndarray]] = []
    objects = _Objects()
    passes = data_pass_switches(getattr(depsgraph, "view_layer", None))
    if passes.uv:
        materials.uv_pass_slot = materials.exporter.slots.uv("")
    pieces = _gather(depsgraph, warnings, read, materials)
    surface = SurfaceCollector(materials.exporter.slots)
    pass_index: list[np.ndarray] = []
    has_uv: list[np.ndarray] = []  # per triangle: its mesh has the render UV map (the UV pass's A)
    flat: list[np.ndarray] = []  # per triangle: shaded flat (``ExportedGeometry.triangle_flat``)
    terminator: list[np.ndarray] = []  # per triangle: ``ExportedGeometry.triangle_terminator``
    clouds, strands = [], []
    velocities: list[np.ndarray | None] = []  # per part: its vertices' velocity attribute (world), or None
    for piece in pieces:
        matrices = np.asarray(piece.matrices, dtype=np.float64).reshape(-1, 4, 4)
        lookup = materials.slot_lookup(piece.geometry.slot_materials, owner=id(piece))
        if isinstance(piece.geometry, LocalPoints):
            clouds.append((piece, matrices, lookup))
            continue
        if isinstance(piece.geometry, LocalHair):
            strands.append((piece, matrices, lookup))
            continue
        local = piece.geometry
        placed = instance_triangles(local.vertices, local.triangles, local.corner_normals, matrices)
        slots = lookup[np.clip(local.slot_index, 0, len(lookup) - 1)]
        parts.append((placed, np.tile(slots, len(matrices))))
        velocities.append(None if local.velocity is None else placed_velocity(local.velocity, len(local.vertices),
                                                                               matrices))
        objects.add(piece, matrices)
        surface.add_mesh(local, matrices, piece.infos, np.linalg.det(matrices[:, :3, :3]) < 0)
        flat.append(np.tile(local.flat if local.flat is not None else np.zeros(len(local.triangles), bool),
                            len(matrices)))
        terminator.append(np.stack([np.where(flat[-1], 0.0, piece.terminator[0]),
                                    np.full(len(flat[-1]), piece.terminator[1])], axis=-1).astype(np.float32))
        if passes.uv:
            has_uv.append(np.full(len(local.triangles) * len(matrices), materials.uv_pass_slot in local.uvs))
        if passes.object_index:  # instance by instance, as ``instance_triangles`` places them
            pass_index.append(np.repeat(np.asarray([info[1] for info in piece.infos], np.float32),
                                        len(local.triangles)))
    geometry = _assemble(parts, objects.names, materials.materials)
    geometry.points = _points(clouds, objects, surface)
    if any(velocity is not None for velocity in velocities):
        geometry.vertex_velocity = np.concatenate([
            np.full((len(placed.vertices), 3), np.nan) if velocity is None else velocity
            for (placed, _), velocity in zip(parts, velocities)])
    if any(piece.geometry.velocity is not None for piece, _, _ in clouds):
        geometry.point_velocity = np.concatenate([
            placed_velocity(piece.geometry.velocity, len(piece.geometry.radii), matrices)
            for piece, matrices, _ in clouds])
    geometry.curves, geometry.curve_velocity = _curves(strands, objects, surface)
    geometry.object_names = list(objects.names)
    geometry.object_asset_names = list(objects.assets)
    geometry.object_matrices = list(objects.matrices)
    geometry.material_names = list(materials.cryptomatte_names)
    geometry.object_light_groups = objects.groups
    geometry.surface = surface.surface()
    geometry.object_flags = np.asarray(objects.flags, np.uint8)
    geometry.triangle_flat = np.concatenate(flat) if flat else np.zeros(0, bool)
    geometry.triangle_terminator = np.concatenate(terminator) if terminator else np.zeros((0, 2), np.float32)
    if passes.object_index:
        geometry.triangle_pass_index = np.concatenate(pass_index) if pass_index else np.zeros(0, np.float32)
    if passes.uv and geometry.surface is not None:
        uv = geometry.surface.uvs[materials.uv_pass_slot]
        present = np.concatenate(has_uv) if has_uv else np.zeros(0, bool)
        geometry.pass_uv = np.concatenate([uv, np.broadcast_to(present[:, None, None], (len(uv), 3, 1))], -1)
    if passes.material_index:
        geometry.material_pass_index = tuple(materials.pass_index)
    return geometry


def _points(clouds, objects: _Objects, surface) -> SpherePoints | None:
    """The points of every point cloud instance (their objects added to ``objects``)."""
    if not clouds:
        return None
    centres, radii, material, owner, instance, pass_index, random = [], [], [], [], [], [], []
    colors = []
    for piece, matrices, lookup in clouds:
        local = piece.geometry
        placed, scaled = place_points(local, matrices)
        count = len(local.radii)
        colors.append((len(scaled), {slot: np.tile(values, (len(matrices), 1))
                                     for slot, values in local.colors.items()}))
        centres.append(placed)
        radii.append(scaled)
        material.append(np.tile(lookup[np.clip(local.slot, 0, len(lookup) - 1)], len(matrices)))
        owner.append(np.full(len(scaled), objects.add(piece, matrices), np.int32))
        rows = surface.add_points(matrices, piece.infos, local.texture_space)
        instance.append(np.repeat(rows, count) if rows is not None else np.full(len(scaled), -1, np.int32))
        pass_index.append(np.repeat(np.asarray([info[1] for info in piece.infos], np.float32), count))
        random.append(np.tile(point_random(count), len(matrices)))
    return SpherePoints(np.concatenate(centres), np.concatenate(radii), np.concatenate(material).astype(np.int32),
                        np.concatenate(owner), np.concatenate(instance).astype(np.int32), np.concatenate(pass_index),
                        np.concatenate(random), stacked_slots(colors, len(surface.slots.attribute_names), (4,)))


def _curves(strands, objects: _Objects, surface):
    """(the strands of every hair instance as round curve segments (their objects added to ``objects``), or None
    without any; their control points' velocity attribute, float64 [P, 3], NaN where a hair has none, or None
    where none has one)."""
    points, radii, offsets, material, owner, instance, pass_index, info = [], [], [], [], [], [], [], []
    colors, uvs, velocities = [], [], []
    first = 0
    for piece, matrices, lookup in strands:
        placed = placed_strands(piece.geometry, matrices)
        if not len(placed.curve_slot):
            continue
        info.append(placed.info)
        colors.append((len(placed.info), placed.colors))
        uvs.append((len(placed.info), placed.uvs))
        segments = np.diff(placed.offsets) - 1  # per strand
        points.append(placed.points)
        velocities.append(placed.velocity)
        radii.append(placed.radii)
        offsets.append(placed.offsets[1:] + first)
        first += len(placed.points)
        material.append(np.repeat(lookup[np.clip(placed.curve_slot, 0, len(lookup) - 1)], segments))
        owner.append(np.full(int(segments.sum()), objects.add(piece, matrices), np.int32))
        per_instance = int(segments.sum()) // len(matrices)
        rows = surface.add_points(matrices, piece.infos, piece.geometry.texture_space)
        instance.append(np.repeat(rows, per_instance) if rows is not None else np.full(int(segments.sum()), -1, np.int32))
        pass_index.append(np.repeat(np.asarray([info[1] for info in piece.infos], np.float32), per_instance))
    if not points:
        return None, None
    every, ends = np.concatenate(points), np.concatenate([[0], *offsets])
    padded, padded_radii, segments = padded_strands(every, np.concatenate(radii), ends)
    velocity = None  # padded as the points are, so it stays row for row with them
    if any(v is not None for v in velocities):
        velocity = padded_strands(np.concatenate([np.full((len(p), 3), np.nan) if v is None else v
                                                  for p, v in zip(points, velocities)]), np.zeros(len(every)), ends)[0]
    return CurveSegments(padded, padded_radii, segments, np.concatenate(material).astype(np.int32),
                         np.concatenate(owner), np.concatenate(instance).astype(np.int32),
                         np.concatenate(pass_index), np.concatenate(info),
                         stacked_slots(colors, len(surface.slots.attribute_names), (2, 4)),
                         stacked_slots(uvs, len(surface.slots.uv_names), (2, 2))), velocity


def _assemble(parts, names, materials) -> ExportedGeometry:
    if not parts:
        return ExportedGeometry(
            vertices=np.zeros((0, 3), np.float64),
            triangles=np.zeros((0, 3), np.int32),
            triangle_material=np.zeros(0, np.int32),
            triangle_object=np.zeros(0, np.int32),
            corner_normals=np.zeros((0, 3, 3), np.float32),
            object_names=[],
            materials=materials or [DEFAULT_MATERIAL],
            vertex_object=np.zeros(0, np.int32),
        )
    offsets = np.cumsum([0] + [len(placed.vertices) for placed, _ in parts[:-1]])
    if offsets[-1] + len(parts[-1][0].vertices) > np.iinfo(np.int32).max:
        from ..tracer.errors import PrismInputError

        raise PrismInputError(
            "The scene has more than 2^31 vertices after instancing, more than Prism can index: "
            "lower the instance count or the subdivision levels."
        )
    return ExportedGeometry(
        vertices=np.concatenate([placed.vertices for placed, _ in parts]),
        triangles=np.concatenate([placed.triangles + offset for (placed, _), offset in zip(parts, offsets)]).astype(np.int32),
        triangle_material=np.concatenate([material for _, material in parts]).astype(np.int32),
        triangle_object=np.concatenate(
            [np.full(len(placed.triangles), index, np.int32) for index, (placed, _) in enumerate(parts)]
        ),
        corner_normals=np.concatenate([placed.corner_normals for placed, _ in parts]),
        object_names=list(names),
        materials=materials,
        vertex_object=np.repeat(np.arange(len(parts), dtype=np.int32),
                                [len(placed.vertices) for placed, _ in parts]),
    )
