"""Small bpy builders the parity scenes share: an empty file, diffuse and emissive materials, planes,
spheres, lights, a camera aimed at a point and a constant world.

Materials are a Diffuse BSDF or an Emission node: the harness compares how each engine reads Blender's
scene settings, so the surfaces are the ones both engines model alike (no GGX variant in play).
"""

from __future__ import annotations

import math

import bpy
from mathutils import Vector


def empty_file(resolution=(48, 48)) -> bpy.types.Scene:
    """A factory-empty file whose scene renders ``resolution`` pixels at 100 %."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return scene


def _shader_material(name: str, node_type: str, inputs: dict) -> bpy.types.Material:
    """A material whose Surface is one ``node_type`` shader with ``inputs`` (socket name → value)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    shader = nodes.new(node_type)
    for socket, value in inputs.items():
        shader.inputs[socket].default_value = value
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(shader.outputs[0], output.inputs["Surface"])
    return material


def diffuse(name: str, colour=(0.5, 0.5, 0.5)) -> bpy.types.Material:
    """A Lambertian material of ``colour`` (linear RGB)."""
    return _shader_material(name, "ShaderNodeBsdfDiffuse", {"Color": (*colour, 1.0)})


def emission(name: str, strength: float, colour=(1.0, 1.0, 1.0)) -> bpy.types.Material:
    """A material emitting ``colour`` × ``strength`` (radiance, W/(m² sr) per unit colour) on both sides."""
    return _shader_material(name, "ShaderNodeEmission", {"Color": (*colour, 1.0), "Strength": strength})


def link_object(obj, collection=None):
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def plane(name: str, size_m: float, location=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0), material=None,
          collection=None) -> bpy.types.Object:
    """A square plane of side ``size_m`` facing +Z before ``rotation`` (Euler, radians)."""
    half = size_m / 2
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(material or diffuse(f"{name} grey"))
    obj = bpy.data.objects.new(name, mesh)
    obj.location, obj.rotation_euler = location, rotation
    return link_object(obj, collection)


def sphere(name: str, radius_m: float, location, material=None, collection=None) -> bpy.types.Object:
    """A smooth UV sphere (32 × 16), linked to ``collection`` (default: the scene's)."""
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius_m, location=location, segments=32, ring_count=16)
    obj = bpy.context.active_object
    obj.name = name
    bpy.ops.object.shade_smooth()
    obj.data.materials.append(material or diffuse(f"{name} grey"))
    if collection is not None:  # the operator linked it to the active collection: move it
        for owner in list(obj.users_collection):
            owner.objects.unlink(obj)
        collection.objects.link(obj)
    return obj


def cube(name: str, size_m: float, location, material=None, collection=None) -> bpy.types.Object:
    bpy.ops.mesh.primitive_cube_add(size=size_m, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material or diffuse(f"{name} grey"))
    if collection is not None:
        for owner in list(obj.users_collection):
            owner.objects.unlink(obj)
        collection.objects.link(obj)
    return obj


def light(name: str, kind: str, power_w: float, location, radius_m: float = 0.0, soft_falloff: bool = False,
          **settings) -> bpy.types.Object:
    """A light of ``kind`` ('POINT', 'SPOT', 'AREA', 'SUN'); ``settings`` are further Light attributes.
    Soft Falloff is off unless asked: the scenes that do not exercise it keep a plain inverse square."""
    data = bpy.data.lights.new(name, kind)
    data.energy = power_w
    if kind in ("POINT", "SPOT"):
        data.shadow_soft_size = radius_m
        data.use_soft_falloff = soft_falloff
    for key, value in settings.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    return link_object(obj)


def camera(location, look_at, lens_mm: float = 35.0) -> bpy.types.Object:
    """The scene's camera at ``location`` looking at ``look_at`` (36 mm sensor)."""
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.lens, cam.data.sensor_width = lens_mm, 36.0
    cam.location = location
    cam.rotation_euler = (Vector(look_at) - Vector(location)).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam
    return cam


def world(strength: float, colour=(1.0, 1.0, 1.0)) -> bpy.types.World:
    """A constant world of radiance ``colour`` × ``strength``."""
    data = bpy.data.worlds.new("World")
    data.use_nodes = True
    background = data.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    bpy.context.scene.world = data
    return data


def stage(world_strength: float = 0.2, bulb_w: float = 300.0):
    """The common set: a grey floor (8 m), a dim white world and a point bulb up and to the left, seen from
    the front and above by a 35 mm camera. Returns the camera."""
    plane("Floor", 8.0, material=diffuse("Floor grey", (0.5, 0.5, 0.5)))
    world(world_strength)
    light("Bulb", "POINT", bulb_w, (-1.5, -1.0, 3.0))
    return camera((0.0, -5.0, 3.0), (0.0, 0.0, 0.4))


def degrees(value: float) -> float:
    return math.radians(value)
