"""World fog rendered by Prism and by Cycles from the same scene, side by side: docs/images/world_fog.png.

    .venv/bin/python tools/world_fog_picture.py [--samples 128]

A floor with three pillars in white fog (the World Output's Volume: Volume Scatter, density 0.12 /m), lit
by a warm point light among the pillars and a cool one behind them. Prints each image's mean luminance and
their ratio (absolute light, no normalisation); the picture shows both with the same view transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "world_fog.png"


def _scene(bpy):
    from helpers.bpy_scenes import add_camera, add_plane, add_point_light
    from helpers.fog_scenes import fog_world

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    fog_world("ShaderNodeVolumeScatter", Density=0.12)
    add_plane("Floor", 30.0, color=(0.5, 0.5, 0.5), specular=0.0)
    for x in (-2.0, 0.0, 2.0):
        bpy.ops.mesh.primitive_cylinder_add(radius=0.25, depth=3.0, location=(x, 2.0, 1.5))
    add_point_light("Warm", 600.0, (0.8, 1.2, 1.2), color=(1.0, 0.6, 0.3))
    add_point_light("Cool", 900.0, (-1.0, 4.5, 2.5), color=(0.4, 0.6, 1.0))
    return add_camera((0.0, -5.0, 1.6), (1.45, 0.0, 0.0), lens_mm=28.0, resolution=(240, 150))


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=128, bounces=8)
