"""Blender's cameras as Cycles renders them: a room of coloured emissive tiles seen through each
projection (perspective with shift and sensor fit, orthographic, equirectangular, both fisheyes) by
Prism and by Cycles; every pixel must see the same tile (direction by direction)."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.cycles import render_cycles_rgba, render_prism_rgba


def _tile_material(name, color):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bsdf.inputs["Specular IOR Level"].default_value = 0.0
    bsdf.inputs["Emission Color"].default_value = (*color, 1.0)
    bsdf.inputs["Emission Strength"].default_value = 1.0
    return material


def coloured_room(half=2.0, tiles=3):
    """A closed box of ``tiles`` x ``tiles`` emissive tiles per wall, each its own colour; returns the palette."""
    rng = np.random.default_rng(5)
    palette = []
    axes = np.eye(3)
    for axis in range(3):
        for sign in (-1.0, 1.0):
            normal = axes[axis] * sign
            u, v = axes[(axis + 1) % 3], axes[(axis + 2) % 3]
            for i in range(tiles):
                for j in range(tiles):
                    color = tuple(rng.random(3) * 0.9 + 0.05)
                    palette.append(color)
                    a0, a1 = -half + 2 * half * i / tiles, -half + 2 * half * (i + 1) / tiles
                    b0, b1 = -half + 2 * half * j / tiles, -half + 2 * half * (j + 1) / tiles
                    corners = [tuple(normal * half + u * a + v * b) for a, b in ((a0, b0), (a1, b0), (a1, b1), (a0, b1))]
                    mesh = bpy.data.meshes.new(f"tile{len(palette)}")
                    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
                    mesh.materials.append(_tile_material(f"tile{len(palette)}", color))
                    obj = bpy.data.objects.new(f"tile{len(palette)}", mesh)
                    bpy.context.scene.collection.objects.link(obj)
    return np.array(palette)


def _camera(kind, resolution, **settings):
    scene = bpy.context.scene
    data = bpy.data.cameras.new("Camera")
    camera = bpy.data.objects.new("Camera", data)
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.location = (0.3, -0.4, 0.2)
    camera.rotation_euler = (math.radians(80), math.radians(10), math.radians(25))
    data.type = kind
    for name, value in settings.items():
        setattr(data, name, value)
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return camera


CASES = {
    "perspective, shift, vertical fit": ("PERSP", (40, 28), dict(lens=24.0, shift_x=0.15, shift_y=-0.1,
                                                                  sensor_fit="VERTICAL", sensor_height=20.0)),
    "orthographic": ("ORTHO", (40, 28), dict(ortho_scale=3.0, shift_x=0.1, sensor_fit="AUTO")),
    "equirectangular": ("PANO", (64, 32), dict(panorama_type="EQUIRECTANGULAR")),
    "equirectangular, limits": ("PANO", (48, 32), dict(panorama_type="EQUIRECTANGULAR", longitude_min=-1.2,
                                                        longitude_max=2.0, latitude_min=-0.6, latitude_max=1.1)),
    "fisheye equidistant": ("PANO", (40, 40), dict(panorama_type="FISHEYE_EQUIDISTANT", fisheye_fov=math.radians(200))),
    "fisheye equisolid": ("PANO", (48, 32), dict(panorama_type="FISHEYE_EQUISOLID", fisheye_lens=8.0,
                                                   fisheye_fov=math.radians(180))),
}


@pytest.mark.parametrize("case", list(CASES))
def test_every_pixel_sees_the_tile_cycles_sees(prism_addon, fresh_scene, case):
    kind, resolution, settings = CASES[case]
    fresh_scene.world = None
    palette = coloured_room()
    _camera(kind, resolution, **settings)
    fresh_scene.prism.max_bounces = 0
    prism = render_prism_rgba(fresh_scene, samples=8)[..., :3]
    cycles = render_cycles_rgba(fresh_scene, samples=8, max_bounces=0)[..., :3]
    black = np.zeros((1, 3))
    palette = np.concatenate([palette, black])  # outside a fisheye's circle
    nearest = lambda image: np.argmin(((image[..., None, :] - palette) ** 2).sum(-1), axis=-1)  # noqa: E731
    tiles, reference = nearest(prism), nearest(cycles)
    # Pixels on a tile's edge mix two colours and may round either way: judge the others (a pixel whose
    # four neighbours see its tile in Cycles' image), which must all agree.
    edge = np.zeros(reference.shape, bool)
    for axis in (0, 1):
        for step in (1, -1):
            edge |= np.roll(reference, step, axis) != reference
    interior = ~edge
    assert interior.mean() > 0.2
    same = (tiles == reference)[interior].mean()
    print(f"MEASURED {case}: {100 * same:.2f} % of interior pixels, {100 * (tiles == reference).mean():.2f} % of all "
          "pixels see Cycles' tile")
    assert same > 0.99, f"{case}: {100 * same:.1f} % of the interior pixels see the same tile"
    assert (tiles == reference).mean() > 0.8
    assert np.median(np.abs(prism - cycles).max(-1)) < 0.03
