"""A moving groom and point cloud, motion blurred, Prism and Cycles side by side: docs/images/motion_blur_geometry.png.

    .venv/bin/python tools/motion_blur_geometry_picture.py [--samples 64]

300 curved, tapering strands ("3D Curves", Diffuse) and 25 diffuse points of radius 6 cm, each keyed to move 0.6 m
along x per frame at constant speed, Render ▸ Motion Blur on with Shutter 0.5 frame centred on the frame (0.3 m
of travel while it is open), under a sun and a grey world. Prints each image's mean luminance and their ratio
(absolute light, no normalisation); the picture shows both with the same view transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "motion_blur_geometry.png"
SPEED_M = 0.6  # per frame, along x


def _scene(bpy):
    from helpers.hair_scenes import groom, hair_object, lit
    from helpers.node_scenes import camera, material, node, slide_during_shutter
    from helpers.point_scenes import points_object

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    lit(scene)
    looks = []
    for name, colour in (("Hair", (0.7, 0.45, 0.25)), ("Clay", (0.3, 0.5, 0.7))):
        mat, nodes, link = material(name)
        link(node(nodes, "ShaderNodeBsdfDiffuse", Color=colour).outputs[0], nodes["Output"].inputs["Surface"])
        looks.append(mat)
    sizes, positions, radii = groom()
    hair = hair_object("Groom", sizes, positions, radii=radii)
    hair.data.materials.append(looks[0])
    slide_during_shutter(hair, scene, SPEED_M, -0.8)
    grid = [(x, y, z) for x in (-0.4, -0.2, 0.0, 0.2, 0.4) for y in (0.0,) for z in (0.1, 0.3, 0.5, 0.7, 0.9)]
    cloud = points_object("Dust", grid, looks[1], radius=0.06)
    slide_during_shutter(cloud, scene, SPEED_M, 0.8)
    camera((0.0, -4.2, 1.0), (0.0, 0.0, 0.5), resolution=(240, 120))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
