"""Build Prism's sky demo and save it as a .blend file.

    python demo/build_sky_scene.py renders/sky.blend      (bpy module)

Three spheres on a pale stone floor under Blender's Nishita sky with the Sun 30° above the horizon:
flint glass (N-SF11 from the catalogue, dispersive), gold (measured n,k) and a white diffuse ball. The
sky and the Sun disc are evaluated per wavelength (docs/worlds.md), so the warm Sun, the blue sky
light in the shadows and the glass's coloured caustic come from one spectral model. Render the same
file with Cycles (demo/render_cycles.py) to compare.
Needs the Prism add-on registered (its settings live on the data-blocks).
"""

import math
import sys
from pathlib import Path

import bpy

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from build_demo_scene import add_mesh_object, new_scene, principled, run  # noqa: E402

SUN_ELEVATION_DEG = 30.0
SUN_ROTATION_DEG = 150.0  # the Sun behind the spheres' left, so shadows and caustics fall toward the camera


def sphere(name, material, location, radius):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=radius, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)
    bpy.ops.object.shade_smooth()
    return obj


def floor_mesh():
    mesh = bpy.data.meshes.new("Floor")
    size = 40.0
    mesh.from_pydata([(-size, -size, 0), (size, -size, 0), (size, size, 0), (-size, size, 0)], [], [(0, 1, 2, 3)])
    return mesh


def sky_world():
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    sky = nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.sun_elevation = math.radians(SUN_ELEVATION_DEG)
    sky.sun_rotation = math.radians(SUN_ROTATION_DEG)
    links.new(sky.outputs["Color"], nodes["Background"].inputs["Color"])
    return world


def build(path: Path) -> None:
    scene = new_scene(480, 270)
    scene.view_settings.view_transform, scene.view_settings.exposure = "AgX", -3.0

    add_mesh_object("Floor", floor_mesh(), principled("Stone", (0.55, 0.52, 0.48), Roughness=1.0))
    glass = principled("Flint glass", (1, 1, 1), Roughness=0.0, **{"Transmission Weight": 1.0, "IOR": 1.7847})
    glass.prism.glass_source, glass.prism.glass_name = "CATALOGUE", "N-SF11"
    sphere("Glass ball", glass, (-0.9, 0.3, 0.5), 0.5)
    gold = principled("Gold", (1.0, 0.78, 0.34), Roughness=0.15, Metallic=1.0)
    gold.prism.conductor = "AU"
    sphere("Gold ball", gold, (0.35, 0.9, 0.45), 0.45)
    sphere("White ball", principled("White", (0.8, 0.8, 0.8), Roughness=1.0), (1.3, -0.2, 0.35), 0.35)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 35.0
    camera.location, camera.rotation_euler = (0.2, -5.0, 1.4), (math.radians(80), 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.world = sky_world()
    path.parent.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=str(path.resolve()))


if __name__ == "__main__":
    run(build, "renders/sky.blend", "Sky scene")
