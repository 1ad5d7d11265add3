"""True displacement rendered by Prism and by Cycles from the same scene, side by side:
docs/images/displacement.png.

    .venv/bin/python tools/displacement_picture.py [--samples 64]

A smooth-shaded grid (2 m, 160 × 160 faces) whose material displaces it by a Wave texture (Material ▸ Settings
▸ Displacement "Displacement Only", Scale 0.15 m) and a sphere displaced by a Noise texture ("Both"), under a
low sun and a dim sky. Prints each image's mean luminance and their ratio (absolute light, no normalisation).
"""

from __future__ import annotations

import math
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "displacement.png"


def _displaced(bpy, name, method, texture, scale, colour):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.displacement_method = method
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes["Principled BSDF"].inputs["Base Color"].default_value = (*colour, 1.0)
    nodes["Principled BSDF"].inputs["Roughness"].default_value = 0.6
    height = nodes.new(texture)
    displacement = nodes.new("ShaderNodeDisplacement")
    displacement.inputs["Scale"].default_value = scale
    links.new(height.outputs["Fac"], displacement.inputs["Height"])
    links.new(displacement.outputs[0], nodes["Material Output"].inputs["Displacement"])
    return material


def _scene(bpy):
    from helpers.bpy_scenes import add_camera

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    world = bpy.data.worlds.new("Sky")
    world.color = (0.05, 0.07, 0.1)
    bpy.context.scene.world = world
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=160, y_subdivisions=160, size=2.0)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(
        _displaced(bpy, "Ridges", "DISPLACEMENT", "ShaderNodeTexWave", 0.15, (0.8, 0.7, 0.55)))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(0.35, 0.2, 0.45), segments=96, ring_count=48)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(
        _displaced(bpy, "Rock", "BOTH", "ShaderNodeTexNoise", 0.08, (0.5, 0.55, 0.6)))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, math.radians(2.0)
    sun.rotation_euler = (math.radians(62.0), 0.0, math.radians(25.0))
    bpy.context.scene.collection.objects.link(sun)
    return add_camera((0.0, -2.3, 1.5), (math.radians(58.0), 0.0, 0.0), lens_mm=40.0, resolution=(240, 160))


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=4)
