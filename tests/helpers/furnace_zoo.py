"""A furnace zoo: spheres of GGX-based shaders under a uniform white world, seen by an orthographic
camera from above, for comparing Prism with Cycles in absolute luminance (a sphere that neither absorbs
nor emits renders as the sky, 1). Each patch is the inner disc of a sphere (radius 0.8 of it in the image:
the rim, where a pixel straddles the sky, is left out)."""

from __future__ import annotations

import bpy
import numpy as np

from .node_scenes import node, surface_material, uv_sphere

SPACING = 2.6  # metres between sphere centres (radius 1)
PIXELS_PER_METRE = 14.0
INNER = 0.8


def principled(distribution="MULTI_GGX", **inputs):
    def build(nodes, link):
        bsdf = node(nodes, "ShaderNodeBsdfPrincipled", **inputs)
        bsdf.distribution = distribution
        return bsdf.outputs[0]
    return build


def one_node(kind, distribution="MULTI_GGX", **inputs):
    def build(nodes, link):
        bsdf = node(nodes, kind, **inputs)
        bsdf.distribution = distribution
        return bsdf.outputs[0]
    return build


def build_furnace_zoo(patches):
    """One sphere per (name, builder) of ``patches`` in a row under a white world of strength 1; returns
    boolean masks [H, W] of the patches (row 0 on top)."""
    scene = bpy.context.scene
    world = bpy.data.worlds.new("White")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    background.inputs["Strength"].default_value = 1.0
    scene.world = world
    count = len(patches)
    xs = (np.arange(count) - 0.5 * (count - 1)) * SPACING
    for (name, build), x in zip(patches, xs):
        uv_sphere(name, 1.0, (float(x), 0.0, 0.0), mat=surface_material(name, build), segments=64, rings=32)
    width_m = count * SPACING
    height_m = SPACING
    data = bpy.data.cameras.new("Top")
    data.type, data.ortho_scale = "ORTHO", width_m
    cam = bpy.data.objects.new("Top", data)
    cam.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    width, height = int(round(width_m * PIXELS_PER_METRE)), int(round(height_m * PIXELS_PER_METRE))
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    px = (np.arange(width) + 0.5) / PIXELS_PER_METRE - 0.5 * width_m
    py = 0.5 * height_m - (np.arange(height) + 0.5) / PIXELS_PER_METRE
    gx, gy = np.meshgrid(px, py)
    return [(gx - x) ** 2 + gy ** 2 < INNER**2 for x in xs]
