"""The evaluated depsgraph → the viewport's tracer scene, exporting only what changed.

Each ``view_update`` hands over the depsgraph's updates. Meshes and hair are read once and kept in
object space: a moved object is placed again from the kept copy, an edited one is read again (its
other instances and every other object untouched). Materials, lights and world are exported again
only when an update may touch them, and a change is reported only when the exported values differ,
so a selection or a frame change that alters nothing restarts nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from ..export import _check_something_to_see
from ..export.light_linking import viewport_linking_warnings
from ..export.view_layer_filter import layer_filter
from ..export.lights import export_lights
from ..export.meshes import export_meshes, read_geometry
from ..export.missing_libraries import missing_libraries
from ..export.world import export_world
from ..tracer.scene import Camera, Scene, World

#: ``Scene.camera`` of the viewport's tracer scene: the view itself travels apart (``progressive.Change``).
PLACEHOLDER_CAMERA = Camera(name="Viewport", camera_to_world=np.eye(4), resolution=(1, 1))
_GEOMETRY_TYPES = {"MESH", "CURVES", "CURVE", "FONT", "SURFACE", "META", "EMPTY", "POINTCLOUD", "VOLUME"}


@dataclass
class Updates:
    """What the depsgraph says changed: objects whose geometry must be read again (original names),
    whether instances moved (or appeared, or vanished), and whether materials, lights, world or the
    scene's settings and camera may have changed."""

    reread: set
    placement: bool = False
    materials: bool = False
    lights: bool = False
    world: bool = False
    scene: bool = False
    camera: bool = False

    @classmethod
    def everything(cls) -> Updates:
        return cls(set(), True, True, True, True, True, True)


def classify(depsgraph) -> Updates:
    """The depsgraph's updates since the last ``view_update``, sorted by what they touch."""
    import bpy

    found = Updates(set())
    for update in depsgraph.updates:
        data = update.id
        if isinstance(data, bpy.types.Object):
            kind = data.type
            if kind == "LIGHT":
                found.lights = True
            elif kind == "CAMERA":
                found.camera = True
            elif kind in _GEOMETRY_TYPES:
                if update.is_updated_geometry:
                    found.reread.add(data.original.name)
                    found.placement = True
                    found.materials = True  # slots may have been reassigned
                if update.is_updated_transform:
                    found.placement = True
                    found.camera = True  # it may be the focus object
        elif isinstance(data, (bpy.types.Material, bpy.types.NodeTree, bpy.types.Image, bpy.types.Texture)):
            found.materials = found.world = found.lights = True
        elif isinstance(data, bpy.types.Light):
            found.lights = True
        elif isinstance(data, bpy.types.World):
            found.world = True
        elif isinstance(data, bpy.types.Camera):
            found.camera = True
        elif isinstance(data, bpy.types.Collection):
            found.placement = found.lights = True
        elif isinstance(data, bpy.types.Scene):
            found.scene = found.camera = found.world = True
    return found


def same(a, b) -> bool:
    """Equal values, arrays included (dataclasses, lists and tuples of them, numbers, arrays)."""
    if a is b:
        return True
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.shape == b.shape and np.array_equal(a, b)
    if type(a) is not type(b):
        return False
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if hasattr(a, "__dataclass_fields__"):
        return all(same(getattr(a, f.name), getattr(b, f.name)) for f in fields(a))
    return a == b


class _GeometryCache:
    """Object-space geometry of each piece (``meshes.read_geometry``), kept until its object changes."""

    def __init__(self):
        self.pieces: dict[tuple, object] = {}
        self.requests: dict[tuple, object] = {}  # the per-corner data each kept piece was read with
        self.stale: set[str] = set()
        self.seen: set[tuple] = set()
        self.reads = 0

    def begin(self, stale) -> None:
        self.stale, self.seen = set(stale), set()

    def end(self) -> None:
        """Forget the pieces the last export did not meet (deleted or hidden objects)."""
        self.pieces = {key: value for key, value in self.pieces.items() if key in self.seen}
        self.stale = set()

    def read(self, key, obj, request=None, warn=None):
        self.seen.add(key)
        if key not in self.pieces or key[1] in self.stale or self.requests.get(key) != request:
            self.reads += 1
            geometry = read_geometry(key, obj, request, warn)
            self.pieces[key] = None if geometry is None else replace(geometry, slot_materials=[])
            self.requests[key] = request
        geometry = self.pieces[key]
        # materials straight from the object: a kept reference to an evaluated material could dangle
        return None if geometry is None else replace(geometry, slot_materials=[s.material for s in obj.material_slots])


class SceneSync:
    """The viewport's tracer scene, brought up to date by ``update``."""

    def __init__(self):
        self.scene: Scene | None = None
        self._cache = _GeometryCache()
        self._material_warnings: list[str] = []
        self._light_warnings: list[str] = []
        self._world_warnings: list[str] = []

    @property
    def mesh_reads(self) -> int:
        """Pieces of geometry read from Blender so far (what an edit costs)."""
        return self._cache.reads

    @property
    def warnings(self) -> list[str]:
        return self._material_warnings + self._light_warnings + self._world_warnings

    def update(self, depsgraph, updates: Updates) -> tuple[Scene | None, bool]:
        """(the new tracer scene, or None when nothing it holds changed; whether its triangles changed).
        Raises ``PrismInputError`` for what cannot render (the message names the object)."""
        previous = self.scene
        if previous is None:
            updates = Updates.everything()
        scene = previous
        geometry_changed = False
        if updates.placement or updates.materials:  # materials decide which UV maps and attributes are read
            self._cache.begin(updates.reread)
            warnings: list[str] = []
            exported = export_meshes(depsgraph, warnings, read=self._cache.read)
            self._cache.end()
            self._material_warnings = warnings
            candidate = Scene(
                vertices=exported.vertices, triangles=exported.triangles,
                triangle_material=exported.triangle_material, materials=exported.materials,
                camera=PLACEHOLDER_CAMERA, triangle_object=exported.triangle_object,
                object_names=exported.object_names, corner_normals=exported.corner_normals,
                triangle_flat=exported.triangle_flat,
                lights=previous.lights if previous else [], world=previous.world if previous else World(),
                surface=exported.surface, points=exported.points, curves=exported.curves,
            )
            geometry_changed = previous is None or not all(
                same(getattr(candidate, name), getattr(previous, name))
                for name in ("vertices", "triangles", "triangle_material", "corner_normals", "surface", "points", "curves"))
            if geometry_changed or not same(candidate.materials, previous.materials):
                scene = candidate if geometry_changed else replace(previous, materials=candidate.materials)
        if updates.lights:
            self._light_warnings = []
            lights = export_lights(depsgraph, self._light_warnings)
            self._light_warnings += viewport_linking_warnings(depsgraph)
            if scene is None or not same(lights, scene.lights):
                scene = replace(scene, lights=lights)
        if updates.world or updates.scene:
            self._world_warnings = []
            world = export_world(depsgraph.scene, self._world_warnings, depsgraph.view_layer)
            if not same(world, scene.world):
                scene = replace(scene, world=world)
        if scene is previous:
            return None, False
        missing = missing_libraries(depsgraph.scene) if scene.triangle_count == 0 else ()
        _check_something_to_see(depsgraph.scene.name, scene, missing, included=layer_filter(depsgraph.view_layer))
        self.scene = scene
        return scene, geometry_changed
