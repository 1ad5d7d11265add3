"""Subsurface scattering rendered by Prism and by Cycles from the same scene, side by side: docs/images/subsurface.png.

    .venv/bin/python tools/subsurface_picture.py [--samples 128]

Three objects on a grey floor under a sun from behind and to the right and a grey world: a wax-like candle
(Principled, Subsurface Weight 1, Radius (1, 0.7, 0.4) x 0.05 m), a torus of the skin-like Principled of
tests/blender/test_subsurface.py (Radius (1, 0.2, 0.1) x 0.04 m) and a jade-green ball (the Subsurface Scattering
node, Random Walk (Skin), Radius (0.3, 1, 0.5) x 0.1 m), all random walks. Prints each image's mean luminance
and their ratio (absolute light, no normalisation); the picture shows both with the same view transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "subsurface.png"


def _scene(bpy):
    from helpers.bpy_scenes import add_plane
    from helpers.node_scenes import camera, uv_sphere
    from helpers.subsurface_scenes import principled_skin, subsurface_node, sun_and_grey_world

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    add_plane("Floor", 30.0, color=(0.5, 0.5, 0.5), specular=0.0)
    bpy.ops.mesh.primitive_cylinder_add(radius=0.35, depth=1.2, location=(-1.3, 0.3, 0.6), vertices=64)
    bpy.context.active_object.data.materials.append(
        principled_skin("Wax", "RANDOM_WALK", base_color=(0.9, 0.8, 0.6), radius=(1.0, 0.7, 0.4), scale=0.05))
    bpy.ops.mesh.primitive_torus_add(major_radius=0.5, minor_radius=0.2, location=(0.0, -0.2, 0.6),
                                     rotation=(1.2, 0.0, 0.3), major_segments=64, minor_segments=32)
    bpy.ops.object.shade_smooth()
    bpy.context.active_object.data.materials.append(principled_skin("Skin", "RANDOM_WALK", scale=0.04))
    uv_sphere("Jade", 0.5, (1.3, 0.2, 0.5),
              subsurface_node("Jade", (0.35, 0.75, 0.45), (0.3, 1.0, 0.5), 0.1, "RANDOM_WALK_SKIN"))
    sun_and_grey_world(scene, energy=4.0, angle_deg=3.0, rotation_deg=(-55.0, 0.0, 35.0), grey=0.15)
    camera((0.0, -4.5, 1.5), (0.0, 0.0, 0.5), lens_mm=35.0, resolution=(240, 150))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=128, bounces=8)
