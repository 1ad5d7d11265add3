"""Bake scenes built in bpy and baked with ``bpy.ops.object.bake`` by Prism or Cycles (not a test module)."""

from __future__ import annotations

import bpy
import numpy as np

from helpers.bpy_scenes import shader_material
from helpers.cycles import configure_cycles

IMAGE_PX = 32  # texels a side of the images baked


def uniform_world(color=(1.0, 1.0, 1.0), strength: float = 1.0):
    world = bpy.data.worlds.new("Uniform")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*color, 1.0)
    background.inputs["Strength"].default_value = strength
    bpy.context.scene.world = world
    return world


def node_material(name: str, node_type: str, **inputs):
    """A material of one shader node (inputs by name, underscores for spaces) and, active, the Image Texture
    node of the image a bake writes (``IMAGE_PX`` square, float)."""
    material = shader_material(name, node_type, **inputs)
    nodes = material.node_tree.nodes
    if node_type == "ShaderNodeBsdfGlossy":
        nodes["Glossy BSDF"].distribution = "GGX"  # single scattering, as Prism's GGX
    target = nodes.new("ShaderNodeTexImage")
    target.image = bpy.data.images.new(f"{name} bake", IMAGE_PX, IMAGE_PX, float_buffer=True)
    nodes.active = target
    return material


def uv_plane(name: str, size_m: float, material=None, location=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0)):
    """A square plane (facing +Z before ``rotation``) whose UV map spans the unit square."""
    half = size_m / 2
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    uv = mesh.uv_layers.new(name="UVMap").data
    for corner, coordinate in enumerate(((0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0))):
        uv[corner].uv = coordinate
    if material is not None:
        mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    obj.location, obj.rotation_euler = location, rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def baked_image(material) -> np.ndarray:
    """The pixels of ``material``'s active Image Texture node: float32 [H, W, 4], row 0 at the bottom."""
    image = material.node_tree.nodes.active.image
    pixels = np.empty(len(image.pixels), np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(image.size[1], image.size[0], 4)


def bake(scene, engine: str, obj, bake_type: str, samples: int = 64, also_selected=(), keep_samples_per_pass=False,
         **options) -> np.ndarray:
    """Bake ``obj`` (the active object, selected with ``also_selected`` only) with ``engine`` ("PRISM" or
    "CYCLES", set up as the comparisons render; Prism in one pass of samples unless
    ``keep_samples_per_pass``) into its material's image; ``options`` go to ``bpy.ops.object.bake`` (e.g.
    ``pass_filter``). Returns the baked pixels (``baked_image``)."""
    previous = scene.render.engine
    if engine == "CYCLES":
        configure_cycles(scene, samples, max_bounces=8)
    else:
        scene.render.engine = "PRISM"
        scene.prism.samples = samples
        if not keep_samples_per_pass:
            scene.prism.samples_per_pass = samples
        scene.prism.seed = 0
    for other in scene.objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    for chosen in (obj, *also_selected):
        chosen.select_set(True)
    try:
        outcome = bpy.ops.object.bake(type=bake_type, margin=0, use_clear=True, **options)
    finally:
        scene.render.engine = previous
    assert outcome == {"FINISHED"}, outcome
    return baked_image(obj.active_material).copy()
