"""Blender scene → ``engine.tracer.scene.Scene``: the export layer.

Reads the evaluated depsgraph (modifiers and instances applied) with
``foreach_get`` into numpy. Each kind of data-block has its own module.
"""

from ..tracer.errors import PrismInputError
from ..tracer.scene import Scene
from .camera import export_camera
from .lights import export_lights
from .meshes import export_meshes
from .world import export_world

__all__ = ["PrismInputError", "export_camera", "export_scene"]


def export_scene(depsgraph) -> Scene:
    """Build the tracer scene from an evaluated depsgraph.

    Raises ``PrismInputError`` (naming the object and the fix) for scenes that
    cannot render: no camera, unsupported camera, NaN geometry, ...
    """
    scene = depsgraph.scene
    camera = export_camera(scene)
    geometry = export_meshes(depsgraph)
    tracer_scene = Scene(
        vertices=geometry.vertices,
        triangles=geometry.triangles,
        triangle_material=geometry.triangle_material,
        triangle_object=geometry.triangle_object,
        object_names=geometry.object_names,
        corner_normals=geometry.corner_normals,
        materials=geometry.materials,
        camera=camera,
        lights=export_lights(depsgraph),
        world=export_world(scene),
    )
    tracer_scene.validate()
    return tracer_scene
