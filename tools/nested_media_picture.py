"""Nested media rendered by Prism and by Cycles from the same scene, side by side: docs/images/nested_media.png.

    .venv/bin/python tools/nested_media_picture.py [--samples 128]

A cube of haze (Volume Scatter) holding an amber glass marble (Glass BSDF with a Volume Absorption inside), a
blue marble outside it, in thin World fog, lit by a warm and a cool point light. Inside the amber marble the
path is in three media at once (the World's fog, the haze, the glass's absorption), added as Cycles adds the
volumes on its stack. Prints each image's mean luminance and their ratio (absolute light, no normalisation).
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "nested_media.png"


def _marble(bpy, name, location, radius, colour):
    from helpers.bpy_scenes import shader_material

    material = shader_material(name, "ShaderNodeBsdfGlass", IOR=1.5, Roughness=0.0)
    nodes = material.node_tree.nodes
    absorption = nodes.new("ShaderNodeVolumeAbsorption")
    absorption.inputs["Color"].default_value = (*colour, 1.0)
    absorption.inputs["Density"].default_value = 1.5
    material.node_tree.links.new(absorption.outputs[0], nodes["Material Output"].inputs["Volume"])
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=48, ring_count=24)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(material)


def _scene(bpy):
    from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
    from helpers.fog_scenes import fog_world

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    fog_world("ShaderNodeVolumeScatter", Density=0.03)
    add_plane("Floor", 30.0, color=(0.5, 0.5, 0.5), specular=0.0)
    haze = shader_material("Haze", "ShaderNodeVolumeScatter", output="Volume", Color=(0.9, 0.92, 0.95, 1.0),
                           Density=0.5, Anisotropy=0.3)
    bpy.ops.mesh.primitive_cube_add(size=2.4, location=(0.6, 1.5, 1.2))
    bpy.context.active_object.data.materials.append(haze)
    _marble(bpy, "Amber glass", (0.6, 1.5, 1.0), 0.6, (0.9, 0.5, 0.15))
    _marble(bpy, "Blue glass", (-1.6, 1.2, 0.5), 0.5, (0.25, 0.5, 0.9))
    add_point_light("Warm", 700.0, (2.2, 0.2, 3.0), color=(1.0, 0.7, 0.4))
    add_point_light("Cool", 500.0, (-1.5, 4.0, 2.5), color=(0.5, 0.7, 1.0))
    return add_camera((0.0, -4.5, 1.6), (1.42, 0.0, 0.0), lens_mm=28.0, resolution=(240, 150))


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=128, bounces=16)
