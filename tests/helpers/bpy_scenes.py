"""Small bpy scene builders shared by the Blender tests."""

from __future__ import annotations

import os
import tempfile

import bpy
import numpy as np


def add_plane(name: str, size_m: float, color=(0.5, 0.5, 0.5), location=(0.0, 0.0, 0.0), specular=0.5):
    """A square plane facing +Z with a Principled material of ``color``; ``specular`` is its Specular IOR
    Level (0: no specular layer, a Lambertian surface as closed forms assume)."""
    half = size_m / 2
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    material = bpy.data.materials.new(f"{name} material")
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1.0)
    material.node_tree.nodes["Principled BSDF"].inputs["Specular IOR Level"].default_value = specular
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def shader_material(name: str, node_type: str, output: str = "Surface", **inputs):
    """A material whose Material Output's ``output`` socket takes one shader node of ``node_type`` (the
    Principled BSDF of a new material removed), its inputs set by name (underscores for spaces)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    shader = nodes.new(node_type)
    for socket, value in inputs.items():
        shader.inputs[socket.replace("_", " ")].default_value = value
    material.node_tree.links.new(shader.outputs[0], nodes["Material Output"].inputs[output])
    return material


def add_point_light(name: str, power_w: float, location, color=(1.0, 1.0, 1.0)):
    data = bpy.data.lights.new(name, "POINT")
    data.energy, data.color, data.shadow_soft_size = power_w, color, 0.0
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_camera(location, rotation_euler, lens_mm: float = 50.0, resolution=(32, 32)):
    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location, camera.rotation_euler = location, rotation_euler
    camera.data.lens = lens_mm
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return camera


def coarse_sphere_under_low_sun(resolution=(32, 32)):
    """A white smooth-shaded UV sphere of 12 segments and 6 rings (Principled, Roughness 1, no specular), lit by a
    sun 80° off the camera's axis (from its right, 10° toward it), in a black world: the shadow terminator runs
    down the middle of the frame. Returns the sphere."""
    import math

    bpy.ops.mesh.primitive_uv_sphere_add(segments=12, ring_count=6, radius=1.0)
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    material = bpy.data.materials.new("White")
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    principled.inputs["Roughness"].default_value = 1.0
    principled.inputs["Specular IOR Level"].default_value = 0.0
    sphere.data.materials.append(material)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, 0.0
    sun.rotation_euler = (math.radians(90.0), 0.0, math.radians(80.0))
    bpy.context.scene.collection.objects.link(sun)
    add_camera((0.0, -4.0, 0.0), (math.radians(90.0), 0.0, 0.0), resolution=resolution)
    world = bpy.data.worlds.new("Black")
    world.color = (0.0, 0.0, 0.0)
    bpy.context.scene.world = world
    return sphere


def image_pixels(path) -> np.ndarray:
    """The pixels of the image file at ``path`` as Blender loads them: float32 [H, W, 4], bottom row first."""
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)


def render_linear_rgb(scene, samples: int, seed: int = 0) -> np.ndarray:
    """Render ``scene`` with Prism through ``bpy.ops.render.render``; scene-linear [H, W, 3], row 0 on top."""
    scene.render.engine = "PRISM"
    scene.prism.samples = samples
    scene.prism.seed = seed
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR", "32"
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "render.exr")
        scene.render.filepath = path
        scene.render.use_file_extension = False
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(path)
        width, height = image.size
        pixels = np.empty(width * height * 4, np.float32)
        image.pixels.foreach_get(pixels)
        bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1, :, :3]


def build_lit_card_scene(resolution=(24, 16)):
    """A grey floor, a red card above it and a point light: lit geometry with a shadow."""
    add_plane("Floor", 6.0, color=(0.6, 0.6, 0.6))
    add_plane("Card", 0.8, color=(0.8, 0.2, 0.1), location=(0.0, 0.0, 0.5))
    add_point_light("Bulb", 300.0, (0.3, 0.2, 2.0))
    return add_camera((0.0, -3.0, 2.5), (0.9, 0.0, 0.0), resolution=resolution)
