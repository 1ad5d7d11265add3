"""UDIM image textures as Cycles renders them: tile 1001 + u + 10 v covers texture coordinates
[u, u + 1] × [v, v + 1], each tile read from its own file, from the bytes packed for it in the .blend, or
from Blender's generation settings, a tile the image lacks magenta.

A square of emission seen straight on by an orthographic camera, its UVs scaled to [0, 3] × [0, 2]: six
tile regions, three with pixels (each a flat colour, so the closed form is the colour's scene-linear
value) and three without (magenta). Prism is compared with that closed form and with Cycles rendering the
same scene, in absolute values."""

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


def _srgb_to_linear(v):
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def _level_to_linear(level):
    """Scene-linear value of the 8-bit sRGB ``level``."""
    return _srgb_to_linear(level / 255.0)


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


def _render_and_compare(scene, expected):
    """Renders ``scene`` with Prism and Cycles and checks each tile region against ``expected`` {tile: rgb}
    (magenta for tiles not named) and Prism against Cycles; returns (prism, cycles) region means."""
    prism = _region_means(render_prism_rgba(scene, 4))
    cycles = _region_means(render_cycles_rgba(scene, 4))
    print("largest |prism - closed form|, |prism - cycles|, |cycles - closed form| per tile:",
          {n: [round(float(np.max(np.abs(a - b))), 4) for a, b in ((prism[n], expected.get(n, MAGENTA)),
                                                                  (prism[n], cycles[n]),
                                                                  (cycles[n], expected.get(n, MAGENTA)))]
           for n in prism})
    for number in (1001, 1002, 1003, 1011, 1012, 1013):
        closed_form = expected.get(number, MAGENTA)
        assert cycles[number] == pytest.approx(closed_form, abs=2e-3), (number, "Cycles' own closed form")
        assert prism[number] == pytest.approx(closed_form, rel=0.02, abs=0.01), (number, prism[number])
        assert prism[number] == pytest.approx(cycles[number], rel=0.02, abs=0.01), number
    return prism, cycles


def _export_warnings(prism_addon):
    export = __import__(f"{prism_addon.__name__}.engine.export", fromlist=["export_scene"])
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    return warnings


def test_udim_tiles_render_their_own_files_and_missing_tiles_magenta_as_in_cycles(prism_addon, fresh_scene,
                                                                                   tmp_path):
    _udim_square(_write_tiles(tmp_path, LEVELS))
    _render_and_compare(fresh_scene, {n: [_level_to_linear(c) for c in levels] for n, levels in LEVELS.items()})


def test_packed_udim_tiles_render_their_packed_bytes_as_in_cycles(prism_addon, fresh_scene, tmp_path):
    image = _write_tiles(tmp_path, LEVELS)
    image.pack()  # one packed PNG per tile, as Pack Resources makes
    assert sorted(p.tile_number for p in image.packed_files) == sorted(LEVELS)
    for path in tmp_path.iterdir():
        path.unlink()  # only the packed bytes are left
    _udim_square(image)
    assert _export_warnings(prism_addon) == []
    _render_and_compare(fresh_scene, {n: [_level_to_linear(c) for c in levels] for n, levels in LEVELS.items()})
    assert not any(tmp_path.iterdir())


#: Tiles of more than 8 bits a channel (stored values), which Blender loads into float buffers made
#: scene-linear from the image's colour space, as Cycles decodes them.
DEEP = {1001: (0.6, 0.3, 0.1), 1002: (0.2, 0.5, 0.8), 1011: (0.9, 0.9, 0.1)}


def _write_deep_tiles(prism_addon, folder, extension, pixel_format):
    """Files ``deep.<tile>.<extension>`` of the flat colours ``DEEP`` in OpenImageIO's ``pixel_format``;
    returns {tile: stored values}."""
    openimageio = __import__(f"{prism_addon.__name__}.engine.output.openimageio", fromlist=["import_openimageio"])
    oiio = openimageio.import_openimageio()
    stored = {}
    for number, colour in DEEP.items():
        path = str(folder / f"deep.{number}.{extension}")
        output = oiio.ImageOutput.create(path)
        assert output.open(path, oiio.ImageSpec(8, 4, 3, pixel_format)), oiio.geterror()
        output.write_image(np.tile(np.array(colour, np.float32), (4, 8, 1)))
        output.close()
        stored[number] = [float(np.float16(c)) if pixel_format == "half" else round(c * 65535) / 65535
                          for c in colour]
    return stored


@pytest.mark.parametrize("extension, pixel_format", [("exr", "half"), ("png", "uint16")])
def test_deep_udim_tiles_are_decoded_from_the_image_colour_space_as_in_cycles(prism_addon, fresh_scene, tmp_path,
                                                                             extension, pixel_format):
    stored = _write_deep_tiles(prism_addon, tmp_path, extension, pixel_format)
    image = bpy.data.images.load(str(tmp_path / f"deep.1001.{extension}"))
    image.source = "TILED"
    image.colorspace_settings.name = "sRGB"  # not Blender's choice for an EXR: its values are decoded anyway
    _udim_square(image)
    assert _export_warnings(prism_addon) == []
    _render_and_compare(fresh_scene, {n: [_srgb_to_linear(v) for v in values] for n, values in stored.items()})


#: Generated tiles (colour, float buffer) of an 8-bit image and of a float image: Blender stores an 8-bit
#: tile's colour as levels ⌊255 c + ½⌋ (0.3 → 77, where round-half-even would give 76) in the image's
#: colour space, a float tile's colour taken from sRGB to linear.
GENERATED = {
    "8-bit": {1001: ((0.6, 0.3, 0.1), False), 1002: ((0.2, 0.5, 0.8), False), 1011: ((0.9, 0.9, 0.1), False)},
    "float": {1001: ((0.6, 0.3, 0.1), True), 1002: ((0.2, 0.5, 0.8), True), 1011: ((0.9, 0.9, 0.1), False)},
}


def _generated_udim(tiles, width=8, height=4):
    """A generated UDIM image with Blank tiles ``tiles`` {number: (colour, float buffer)}, the first one
    made with the image (which sets its colour space: sRGB for 8-bit, Linear Rec.709 for float)."""
    numbers = sorted(tiles)
    image = bpy.data.images.new("Generated", width, height, tiled=True, float_buffer=tiles[numbers[0]][1])
    image.generated_color = (*tiles[numbers[0]][0], 1.0)
    for number in numbers[1:]:
        _fill_tile(image, number, tiles[number][0], tiles[number][1], width, height)
    return image


def _fill_tile(image, number, colour, float_buffer, width=8, height=4, generated_type="BLANK"):
    """Adds tile ``number`` to ``image`` and fills it as Image ▸ Fill Tile does."""
    image.tiles.active = image.tiles.new(tile_number=number)
    with bpy.context.temp_override(edit_image=image):
        assert bpy.ops.image.tile_fill(color=(*colour, 1.0), generated_type=generated_type, width=width,
                                       height=height, float=float_buffer, alpha=True) == {"FINISHED"}


def _generated_closed_form(colour, float_buffer, colour_space):
    if float_buffer:
        return [_srgb_to_linear(c) for c in colour]  # the float buffer holds linear values
    levels = [int(np.floor(np.float32(255.0) * np.float32(c) + np.float32(0.5))) for c in colour]
    return [_level_to_linear(level) if colour_space == "sRGB" else level / 255.0 for level in levels]


@pytest.mark.parametrize("kind", GENERATED)
def test_generated_udim_tiles_render_their_fill_colour_as_in_cycles(prism_addon, fresh_scene, kind):
    image = _generated_udim(GENERATED[kind])
    assert image.colorspace_settings.name == {"8-bit": "sRGB", "float": "Linear Rec.709"}[kind]
    assert all(tile.is_generated_tile for tile in image.tiles)
    _udim_square(image)
    assert _export_warnings(prism_addon) == []
    _render_and_compare(fresh_scene, {n: _generated_closed_form(colour, float_buffer, image.colorspace_settings.name)
                                      for n, (colour, float_buffer) in GENERATED[kind].items()})


def test_a_tile_without_a_file_is_named_and_renders_magenta(prism_addon, fresh_scene, tmp_path):
    image = _write_tiles(tmp_path, {1001: LEVELS[1001]})
    image.tiles.new(tile_number=1002)  # in Blender only: no file on disk
    _udim_square(image)
    assert _export_warnings(prism_addon) == [
        "Material 'Paint': the 'Paint' node (Image Texture) cannot read tile 1002 of the UDIM image "
        "'paint.1001.png' (no file on disk, nothing packed or generated for it); Prism renders it magenta, as "
        "Cycles renders a missing tile."]
    prism = _region_means(render_prism_rgba(fresh_scene, 4))
    assert prism[1002] == pytest.approx(MAGENTA, rel=0.02, abs=0.01)
    assert prism[1001] == pytest.approx([_level_to_linear(c) for c in LEVELS[1001]], rel=0.02, abs=0.01)


def test_a_grid_tile_and_a_float_tile_in_an_8_bit_image_are_named(prism_addon, fresh_scene):
    image = _generated_udim({1001: GENERATED["8-bit"][1001]})
    _fill_tile(image, 1002, (0.2, 0.5, 0.8), True)  # float, in an sRGB image whose first tile is 8-bit
    _fill_tile(image, 1011, (0.5, 0.5, 0.5), False, generated_type="UV_GRID")
    _udim_square(image)
    where = "Material 'Paint': the 'Paint' node (Image Texture) "
    assert _export_warnings(prism_addon) == [
        where + "does not draw the generated UV Grid of tile 1011 of the UDIM image 'Generated'; Prism renders it "
                "magenta (Image ▸ Save As writes the tiles to files Prism reads).",
        where + "renders the float pixels of tile 1002 of the UDIM image 'Generated' as scene-linear, as Blender "
                "holds them; Cycles 4.5 decodes them from 'sRGB' again (the image's first tile is 8-bit), which "
                "darkens them."]
    prism = _region_means(render_prism_rgba(fresh_scene, 4))
    cycles = _region_means(render_cycles_rgba(fresh_scene, 4))
    linear = [_srgb_to_linear(c) for c in (0.2, 0.5, 0.8)]
    assert prism[1002] == pytest.approx(linear, rel=0.02, abs=0.01)
    assert cycles[1002] == pytest.approx([_srgb_to_linear(c) for c in linear], abs=2e-3), "decoded twice"
    assert prism[1011] == pytest.approx(MAGENTA, rel=0.02, abs=0.01)
    assert prism[1001] == pytest.approx(cycles[1001], rel=0.02, abs=0.01)


def test_packed_tiles_blender_ignores_are_named_and_the_files_read(prism_addon, fresh_scene, tmp_path):
    image = _write_tiles(tmp_path, {1001: LEVELS[1001], 1002: LEVELS[1002]})
    image.pack()
    image.tiles.new(tile_number=1003)  # two packed files for three tiles: Blender reads the files instead
    _udim_square(image)
    where = "Material 'Paint': the 'Paint' node (Image Texture) "
    assert _export_warnings(prism_addon) == [
        where + "reads the UDIM image 'paint.1001.png' from its files: it has 2 packed files for 3 tiles, and "
                "Blender (so Cycles) ignores packed tiles unless every tile is packed, dropping them when it next "
                "loads a tile.",
        where + "cannot read tile 1003 of the UDIM image 'paint.1001.png' (no file on disk, nothing packed or "
                "generated for it); Prism renders it magenta, as Cycles renders a missing tile."]
    assert len(image.packed_files) == 2, "Prism leaves the packed files alone"


def test_unsaved_paint_on_a_udim_image_is_named(prism_addon, fresh_scene):
    image = _generated_udim(GENERATED["8-bit"])
    image.pixels.foreach_set(np.tile(np.array([0.0, 1.0, 0.0, 1.0], np.float32), 8 * 4))  # paints tile 1001
    assert image.is_dirty
    _udim_square(image)
    assert _export_warnings(prism_addon) == [
        "Material 'Paint': the 'Paint' node (Image Texture) cannot read the unsaved changes of the UDIM image "
        "'Generated' (painted or edited in Blender), which Cycles renders: Prism renders each tile as saved, "
        "packed or generated. Save the image, or pack it (Image ▸ Pack), to render the changes."]
