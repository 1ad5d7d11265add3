"""A Blender Volume object on fire (blackbody light × a temperature grid) rendered by Prism and by Cycles from
the same scene, side by side: docs/images/volume_fire.png.

    .venv/bin/python tools/volume_fire_picture.py [--samples 64]

The 40³ cloud of ``volume_object_picture`` (5 cm voxels) as smoke, and a "temperature" grid in the same file
that is hottest in its lower middle, written with the OpenVDB module Blender bundles. A Principled Volume
(Color 0.2, Density 2, Blackbody Intensity 1, Temperature 1800 K) multiplies its Temperature by that grid
(Cycles' Temperature Attribute), so the fire burns at up to 3600 K and lights a grey floor in a dark world.
Cycles ray marches it at Step Rate 0.1 with the grids at full precision. Prints each image's mean luminance
and their ratio (absolute light); the picture shows both with the same view transform.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from volume_object_picture import SIZE, add_volume, cloud_density, write_vdb

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "volume_fire.png"


def fire_temperature(density: np.ndarray) -> np.ndarray:
    """[SIZE]³ temperature factor: up to 2 in the cloud's lower middle, falling off with the height and
    the distance from the axis, 0 where the cloud has no smoke."""
    x = (np.arange(SIZE) + 0.5) / SIZE - 0.5
    gx, gy, gz = np.meshgrid(x, x, x, indexing="ij")
    core = np.exp(-(gx ** 2 + gy ** 2) / 0.06 - (gz + 0.1) ** 2 / 0.08)
    return (2.0 * core * np.sqrt(density)).astype(np.float32)


def _scene(bpy):
    from helpers.bpy_scenes import add_plane
    from helpers.node_scenes import black_world, camera

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    black_world()
    add_plane("Floor", 20.0, color=(0.5, 0.5, 0.5), specular=0.0)
    path = Path(tempfile.mkdtemp(prefix="prism_fire_")) / "fire.vdb"
    density = cloud_density()
    write_vdb(path, [("density", density), ("temperature", fire_temperature(density))])
    add_volume(bpy, "Fire", path, Color=(0.2, 0.2, 0.2), Density=2.0, Blackbody_Intensity=1.0, Temperature=1800.0)
    camera((0.0, -4.2, 1.5), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(240, 180))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
