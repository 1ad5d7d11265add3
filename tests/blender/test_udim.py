"""UDIM image textures as Cycles renders them: tile 1001 + u + 10 v covers texture coordinates
[u, u + 1] × [v, v + 1], each tile read from its own file, a tile the image lacks magenta.

A square of emission seen straight on by an orthographic camera, its UVs scaled to [0, 3] × [0, 2]: six
tile regions, three with files (each a flat 8-bit sRGB colour, so the closed form is the colour's
scene-linear value) and three without (magenta). Prism is compared with that closed form and with Cycles
rendering the same scene, in absolute values."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import emission_material, node, plane

LEVELS = {1001: (200, 60, 40), 1002: (40, 180, 70), 1011: (60, 80, 210)}  # 8-bit sRGB per tile
MAGENTA = (1.0, 0.0, 1.0)
SIDE = 60  # pixels across the square
MARGIN = 3  # pixels left out at each region's edge (filtering across tile borders)


def _srgb_to_linear(level):
    v = level / 255.0
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def _write_tiles(folder, levels):
    for number, colour in levels.items():
        tile = bpy.data.images.new(f"tile {number}", 8, 4)
        tile.pixels.foreach_set(np.tile(np.array([*(c / 255.0 for c in colour), 1.0], np.float32), 32))
        tile.filepath_raw, tile.file_format = str(folder / f"paint.{number}.png"), "PNG"
        tile.save()
        bpy.data.images.remove(tile)
    image = bpy.data.images.load(str(folder / "paint.1001.png"))
    image.source = "TILED"
    return image


def _udim_square(image):
    def build(nodes, link):
        coordinates = node(nodes, "ShaderNodeTexCoord")
        mapping = node(nodes, "ShaderNodeMapping", Scale=(3.0, 2.0, 1.0))
        texture = node(nodes, "ShaderNodeTexImage")
        texture.image, texture.name = image, "Paint"
        link(coordinates.outputs["UV"], mapping.inputs["Vector"])
        link(mapping.outputs["Vector"], texture.inputs["Vector"])
        return texture.outputs["Color"]

    plane("Square", 2.0, mat=emission_material("Paint", build))
    scene = bpy.context.scene
    data = bpy.data.cameras.new("Front")
    data.type, data.ortho_scale = "ORTHO", 2.0
    camera = bpy.data.objects.new("Front", data)
    camera.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x = scene.render.resolution_y = SIDE
    scene.render.resolution_percentage = 100


def _region_means(rgba):
    """Mean RGB of each tile region's inner pixels: {tile number: rgb} (row 0 of ``rgba`` on top)."""
    means = {}
    for v in range(2):
        for u in range(3):
            x0, x1 = u * SIDE // 3 + MARGIN, (u + 1) * SIDE // 3 - MARGIN
            y1, y0 = SIDE - v * SIDE // 2 - MARGIN, SIDE - (v + 1) * SIDE // 2 + MARGIN
            means[1001 + u + 10 * v] = rgba[y0:y1, x0:x1, :3].reshape(-1, 3).mean(axis=0)
    return means


def test_udim_tiles_render_their_own_files_and_missing_tiles_magenta_as_in_cycles(prism_addon, fresh_scene,
                                                                                   tmp_path):
    _udim_square(_write_tiles(tmp_path, LEVELS))
    prism = _region_means(render_prism_rgba(fresh_scene, 4))
    cycles = _region_means(render_cycles_rgba(fresh_scene, 4))
    print("prism / cycles per tile:", {n: np.round(prism[n] / np.maximum(cycles[n], 1e-6), 4) for n in prism})
    for number in (1001, 1002, 1003, 1011, 1012, 1013):
        expected = [_srgb_to_linear(c) for c in LEVELS[number]] if number in LEVELS else MAGENTA
        assert cycles[number] == pytest.approx(expected, abs=2e-3), (number, "Cycles' own closed form")
        assert prism[number] == pytest.approx(expected, rel=0.02, abs=0.01), (number, prism[number])
        assert prism[number] == pytest.approx(cycles[number], rel=0.02, abs=0.01), number


def test_a_tile_without_a_file_is_named_and_renders_magenta(prism_addon, fresh_scene, tmp_path):
    export = __import__(f"{prism_addon.__name__}.engine.export", fromlist=["export_scene"])
    image = _write_tiles(tmp_path, {1001: LEVELS[1001]})
    image.tiles.new(tile_number=1002)  # in Blender only: no file on disk
    _udim_square(image)
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    assert warnings == ["Material 'Paint': the 'Paint' node (Image Texture) cannot read tile 1002 of the UDIM "
                        "image 'paint.1001.png' (no file on disk: Prism reads each tile's own file); Prism renders "
                        "it magenta, as Cycles renders a missing tile."]
    prism = _region_means(render_prism_rgba(fresh_scene, 4))
    assert prism[1002] == pytest.approx(MAGENTA, rel=0.02, abs=0.01)
    assert prism[1001] == pytest.approx([_srgb_to_linear(c) for c in LEVELS[1001]], rel=0.02, abs=0.01)
