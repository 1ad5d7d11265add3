"""A cloud made of a cube and a Noise Texture (a Density driven by nodes) rendered by Prism and by Cycles from
the same scene, side by side: docs/images/textured_volume.png.

    .venv/bin/python tools/textured_volume_picture.py [--samples 64]

A 2 m cube holds a Principled Volume (Color 0.9, 0.85, 0.8) whose Density is 120 × max(Noise − 0.4, 0) ×
a Quadratic Sphere Gradient Texture over Object coordinates (1 at the centre, 0 from 1 m out), Noise Texture of
Scale 2.5 and Detail 4 over the cube's Generated coordinates: a round cloud of lumps, over a grey floor,
under a blue-grey world and a low sun. Prism bakes the density onto a grid (``tracer.media.baked_density``,
Step Rate 0.5: 160 voxels across); Cycles ray marches it at the same Step Rate. Prints each image's mean
luminance and their ratio (absolute light); the picture shows both with the same view transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "textured_volume.png"


def _cloud_material(bpy):
    from helpers.node_scenes import material, node, noise_ball

    mat, nodes, link = material("Cloud")
    mat.cycles.volume_step_rate = 0.5
    lumps, _ = noise_ball(nodes, link, scale=2.5, detail=4.0, threshold=0.4)
    thick = node(nodes, "ShaderNodeMath", Value_001=120.0)
    thick.operation = "MULTIPLY"
    volume = node(nodes, "ShaderNodeVolumePrincipled", Color=(0.9, 0.85, 0.8))
    link(lumps, thick.inputs[0])
    link(thick.outputs[0], volume.inputs["Density"])
    link(volume.outputs[0], nodes["Output"].inputs["Volume"])
    return mat


def _scene(bpy):
    from helpers.bpy_scenes import add_plane
    from helpers.node_scenes import camera, sun_and_sky

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    sun_and_sky(scene, (0.9, 0.0, 0.8))
    add_plane("Floor", 20.0, color=(0.5, 0.5, 0.5), specular=0.0)
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.0, 0.0, 1.05))
    bpy.context.active_object.data.materials.append(_cloud_material(bpy))
    camera((0.0, -5.5, 1.8), (0.0, 0.0, 1.0), lens_mm=45.0, resolution=(240, 180))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
