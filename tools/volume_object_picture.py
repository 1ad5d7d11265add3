"""A Blender Volume object (an OpenVDB cloud) rendered by Prism and by Cycles from the same scene, side by side:
docs/images/volume_object.png.

    .venv/bin/python tools/volume_object_picture.py [--samples 64]

A 40³ cloud of soft lumps (voxels 5 cm, written with the OpenVDB module Blender bundles, seed 7) as a Volume
object with a Principled Volume (Density 6, Anisotropy 0.3) over a grey floor, under a low warm sun and a
blue-grey sky. Cycles ray marches it at Step Rate 0.1 (1/10 voxel) with the grid at full precision, as
``tests/blender/test_volume_objects.py`` does; Prism tracks it by delta tracking. Prints each image's mean
luminance and their ratio (absolute light); the picture shows both with the same view transform.
"""

from __future__ import annotations

import importlib
import math
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "volume_object.png"
SIZE, VOXEL_M = 40, 0.05


def cloud_density(seed: int = 7) -> np.ndarray:
    """[SIZE]³ density: 14 Gaussian lumps of random size around the middle, clipped to 1."""
    rng = np.random.default_rng(seed)
    x = (np.arange(SIZE) + 0.5) / SIZE - 0.5
    gx, gy, gz = np.meshgrid(x, x, x, indexing="ij")
    density = np.zeros((SIZE,) * 3)
    for _ in range(14):
        centre = rng.normal(0.0, 0.12, 3) * (1.0, 1.0, 0.6)
        radius = rng.uniform(0.08, 0.16)
        density += np.exp(-((gx - centre[0]) ** 2 + (gy - centre[1]) ** 2 + (gz - centre[2]) ** 2) / radius ** 2)
    return np.clip(density, 0.0, 1.0).astype(np.float32)


def write_vdb(path: Path, named_values) -> None:
    """(name, [SIZE]³ values) pairs as float grids of one OpenVDB file, voxels of ``VOXEL_M`` centred on the
    origin, with the OpenVDB module Blender bundles."""
    from render import load_addon_package

    package = load_addon_package()
    vdb = importlib.import_module(f"{package.__name__}.engine.export.volume_grids").openvdb_module()
    grids = []
    for name, values in named_values:
        grid = vdb.FloatGrid()
        grid.name = name
        grid.copyFromArray(values, ijk=(0, 0, 0))
        transform = vdb.createLinearTransform(voxelSize=VOXEL_M)
        transform.postTranslate((-SIZE * VOXEL_M / 2,) * 3)
        grid.transform = transform
        grids.append(grid)
    vdb.write(str(path), grids=grids)


def add_volume(bpy, name: str, path: Path, **principled):
    """A Volume object of the file ``path`` at 1.1 m height, its grids at full precision (as the tests), with
    a Principled Volume of ``principled`` inputs; Cycles set to ray march it at Step Rate 0.1."""
    from helpers.node_scenes import material, node

    volume = bpy.data.volumes.new(name)
    volume.filepath = str(path)
    volume.render.precision = "FULL"
    mat, nodes, link = material(name)
    shader = node(nodes, "ShaderNodeVolumePrincipled", **principled)
    link(shader.outputs[0], nodes["Output"].inputs["Volume"])
    volume.materials.append(mat)
    obj = bpy.data.objects.new(name, volume)
    obj.location = (0.0, 0.0, 1.1)
    scene = bpy.context.scene
    scene.collection.objects.link(obj)
    scene.cycles.volume_step_rate, scene.cycles.volume_max_steps = 0.1, 4096
    return obj


def _scene(bpy):
    from helpers.bpy_scenes import add_plane
    from helpers.node_scenes import black_world, camera

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    world = black_world()
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.45, 0.55, 0.7, 1.0)
    background.inputs["Strength"].default_value = 0.4
    add_plane("Floor", 20.0, color=(0.4, 0.4, 0.4), specular=0.0)
    path = Path(tempfile.mkdtemp(prefix="prism_cloud_")) / "cloud.vdb"
    write_vdb(path, [("density", cloud_density())])
    add_volume(bpy, "Cloud", path, Color=(0.9, 0.9, 0.9), Density=6.0, Anisotropy=0.3)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.color = 4.0, (1.0, 0.85, 0.7)
    sun.rotation_euler = (math.radians(70.0), 0.0, math.radians(40.0))
    scene.collection.objects.link(sun)
    camera((0.0, -4.2, 1.5), (0.0, 0.0, 1.0), lens_mm=50.0, resolution=(240, 180))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
