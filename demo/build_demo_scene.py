"""Build Prism's demo scene and save it as a .blend file.

    python demo/build_demo_scene.py renders/demo.blend      (bpy module)

A small room: a gold monkey (subdivision modifier, measured n,k of gold), a
flint-glass prism (N-SF11 from the glass catalogue), a teal box, a warm 3200 K
blackbody area light and a cool 9000 K point light, so the render shows lit
geometry, soft and hard shadows, colour bleeding and dispersive glass.
Needs the Prism add-on registered (its settings live on the data-blocks).
"""

import math
import sys
from pathlib import Path

import bpy

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from render import exit_now, load_addon_package  # noqa: E402  (the add-on, for its settings)


def principled(name, color, **inputs):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    node = material.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*color, 1.0)
    for socket, value in inputs.items():
        node.inputs[socket].default_value = value
    return material


def add_mesh_object(name, mesh, material, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1)):
    obj = bpy.data.objects.new(name, mesh)
    obj.location, obj.rotation_euler, obj.scale = location, rotation, scale
    obj.data.materials.append(material)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def box_mesh(name):
    mesh = bpy.data.meshes.new(name)
    v = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh.from_pydata(v, [], faces)
    return mesh


def room_mesh():
    """Floor, ceiling, back wall and two side walls, open toward the camera."""
    mesh = bpy.data.meshes.new("Room")
    s, h = 3.0, 3.0
    vertices = [(-s, -s, 0), (s, -s, 0), (s, s, 0), (-s, s, 0), (-s, s, h), (s, s, h), (-s, -s, h), (s, -s, h)]
    faces = [(0, 1, 2, 3), (3, 2, 5, 4), (0, 3, 4, 6), (1, 7, 5, 2), (6, 4, 5, 7)]
    mesh.from_pydata(vertices, [], faces)
    return mesh


def prism_mesh():
    """A 60° prism, 0.8 m long, triangle side 0.6 m."""
    mesh = bpy.data.meshes.new("Prism")
    side, length = 0.6, 0.8
    triangle = [(-side / 2, 0), (side / 2, 0), (0, side * math.sqrt(3) / 2)]
    vertices = [(x, -length / 2, z) for x, z in triangle] + [(x, length / 2, z) for x, z in triangle]
    faces = [(0, 1, 2), (5, 4, 3), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)]
    mesh.from_pydata(vertices, [], faces)
    return mesh


def blackbody(light_data, temperature_k: float) -> None:
    """Light ▸ Temperature, Blender's own (Cycles renders it too); before Blender 4.4 Prism's Colour Source."""
    if hasattr(light_data, "use_temperature"):
        light_data.use_temperature, light_data.temperature = True, temperature_k
    else:
        light_data.prism.color_source, light_data.prism.temperature_k = "BLACKBODY", temperature_k


def new_scene(width: int, height: int):
    """An empty factory-settings scene of ``width`` x ``height`` pixels with the add-on registered."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    if not hasattr(bpy.types.Scene, "prism"):
        load_addon_package().register()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    return scene


def build(path: Path) -> None:
    scene = new_scene(480, 320)

    add_mesh_object("Room", room_mesh(), principled("Walls", (0.75, 0.72, 0.68), Roughness=1.0))
    bpy.ops.mesh.primitive_monkey_add(location=(-0.9, 0.4, 0.55), rotation=(0, 0, math.radians(-20)))
    monkey = bpy.context.active_object
    monkey.name = "Monkey"
    monkey.modifiers.new("Subdivision", "SUBSURF").levels = 2
    gold = principled("Gold", (1.0, 0.78, 0.34), Roughness=0.25, Metallic=1.0)
    gold.prism.conductor = "AU"
    monkey.data.materials.append(gold)
    bpy.ops.object.shade_smooth()
    add_mesh_object("Box", box_mesh("Box"), principled("Teal", (0.05, 0.45, 0.5), Roughness=0.9),
                    location=(1.0, 0.8, 0.35), rotation=(0, 0, math.radians(25)), scale=(0.35, 0.35, 0.35))
    glass = principled("Flint glass", (1, 1, 1), Roughness=0.0, **{"Transmission Weight": 1.0, "IOR": 1.7847})
    glass.prism.glass_source, glass.prism.glass_name = "CATALOGUE", "N-SF11"
    # 1 mm above the floor: a face lying in the floor's plane is ill-posed (which of the two a ray meets is
    # up to each ray tracer), and Cycles then renders the prism's light 1.7 % darker than with a gap.
    add_mesh_object("Glass prism", prism_mesh(), glass, location=(0.45, -0.6, 0.001),
                    rotation=(0, 0, math.radians(10)))

    area_data = bpy.data.lights.new("Key", "AREA")
    area_data.energy, area_data.size = 90.0, 1.0
    blackbody(area_data, 3200.0)
    area = bpy.data.objects.new("Key", area_data)
    area.location, area.rotation_euler = (-1.5, -1.5, 2.9), (math.radians(20), math.radians(-25), 0)
    scene.collection.objects.link(area)
    point_data = bpy.data.lights.new("Fill", "POINT")
    point_data.energy, point_data.shadow_soft_size = 40.0, 0.0
    blackbody(point_data, 9000.0)
    point = bpy.data.objects.new("Fill", point_data)
    point.location = (1.8, -1.2, 1.6)
    scene.collection.objects.link(point)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 32.0
    camera.location, camera.rotation_euler = (0.0, -5.2, 1.5), (math.radians(82), 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    save_with_world(scene, (0.02, 0.025, 0.03), path)


def save_with_world(scene, background, path: Path) -> None:
    """Give ``scene`` a plain ``background`` (linear RGB) world and save the file as ``path``."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*background, 1)
    scene.world = world
    path.parent.mkdir(parents=True, exist_ok=True)
    bpy.ops.wm.save_as_mainfile(filepath=str(path.resolve()))


def run(build, default_path: str, what: str, **options) -> None:
    """A builder's command line: ``build(path, **options)`` to argv's first path (else ``default_path``),
    one line on stderr, and an exit status (``exit_now``: the bpy module may hang at exit)."""
    arguments = [a for a in sys.argv[1:] if not a.startswith("--")]
    target = Path(arguments[0] if arguments else default_path)
    status = 0
    try:
        build(target, **options)
        print(f"{what} written to {target}", file=sys.stderr)
    except Exception as error:  # noqa: BLE001 - report and exit non-zero
        print(f"Could not build the {what.lower()}: {error}", file=sys.stderr)
        status = 1
    exit_now(status)


if __name__ == "__main__":
    run(build, "renders/demo.blend", "Demo scene")
