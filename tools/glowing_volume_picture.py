"""Embers in a ball of smoke (an Emission Strength and a Density driven by nodes) rendered by Prism and by
Cycles from the same scene, side by side: docs/images/glowing_volume.png.

    .venv/bin/python tools/glowing_volume_picture.py [--samples 64]

A 2 m cube holds a Principled Volume (grey smoke) whose Density is 1.5 × a Quadratic Sphere Gradient Texture
over Object coordinates (1 at the centre, 0 from 1 m out) and whose Emission Strength is 150 × max(Noise − 0.5,
0) × that gradient (Noise Texture of Scale 3, Detail 3, Emission Color 1, 0.45, 0.12): glowing lumps inside a
ball of smoke that light a grey floor, under a dim blue world. Prism bakes both the density and the strength
onto one grid (``tracer.media.baked_density``, Step Rate 0.5); Cycles ray marches them at the same Step Rate.
Prints each image's mean luminance and their ratio (absolute light); the picture shows both with the same view
transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "glowing_volume.png"


def _math(nodes, node, operation, **inputs):
    made = node(nodes, "ShaderNodeMath", **inputs)
    made.operation = operation
    return made


def _embers_material():
    from helpers.node_scenes import material, node, noise_ball

    mat, nodes, link = material("Embers")
    mat.cycles.volume_step_rate = 0.5
    lumps, ball = noise_ball(nodes, link, scale=3.0, detail=3.0, threshold=0.5)
    glow = _math(nodes, node, "MULTIPLY", Value_001=150.0)
    smoke = _math(nodes, node, "MULTIPLY", Value_001=1.5)
    volume = node(nodes, "ShaderNodeVolumePrincipled", Color=(0.6, 0.6, 0.6), Emission_Color=(1.0, 0.45, 0.12))
    link(lumps, glow.inputs[0])
    link(ball, smoke.inputs[0])
    link(glow.outputs[0], volume.inputs["Emission Strength"])
    link(smoke.outputs[0], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _scene(bpy):
    from helpers.bpy_scenes import add_plane
    from helpers.node_scenes import black_world, camera

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    background = black_world().node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.3, 0.4, 0.6, 1.0)
    background.inputs["Strength"].default_value = 0.05
    add_plane("Floor", 20.0, color=(0.5, 0.5, 0.5), specular=0.0)
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.0, 0.0, 1.05))
    bpy.context.active_object.data.materials.append(_embers_material())
    camera((0.0, -5.5, 1.8), (0.0, 0.0, 1.0), lens_mm=45.0, resolution=(240, 180))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
