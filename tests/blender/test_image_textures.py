"""Image textures through Blender: texels land where their UVs put them, in the colour the image's colour
space says, for every colour space Blender offers (against Blender's own decoding in Cycles)."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.cycles_compare import LUMINANCE, object_ids, render_cycles, render_prism
from helpers.node_scenes import black_world, camera, emission_material, plane

#: 4 x 4 texels, each its own colour (levels of an 8-bit image, row 0 at the bottom).
LEVELS = np.array([[[40 + 50 * x, 200 - 40 * y, 90 + 30 * ((x + y) % 3)] for x in range(4)] for y in range(4)],
                  np.float64)


def _image(name, colour_space, size=4, levels=LEVELS, float_buffer=False):
    image = bpy.data.images.new(name, size, size, alpha=True, float_buffer=float_buffer)
    image.colorspace_settings.name = colour_space
    pixels = np.ones((size, size, 4), np.float32)
    pixels[..., :3] = levels / 255.0
    image.pixels.foreach_set(pixels.ravel())
    return image


def _image_material(image, interpolation="Closest"):
    def build(nodes, link):
        texture = nodes.new("ShaderNodeTexImage")
        texture.image, texture.interpolation = image, interpolation
        return texture.outputs["Color"]

    return emission_material(image.name, build)


def _srgb_to_linear(v):
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


@pytest.mark.parametrize("colour_space", ["sRGB", "Non-Color"])
def test_checker_image_texels_land_in_place_decoded_by_colour_space(prism_addon, fresh_scene, colour_space):
    """A 4 x 4 image on a UV-mapped plane filling the view, Closest interpolation, as emission: each texel
    covers its 16 x 16 pixels in its decoded colour (sRGB levels through the sRGB curve, Non-Color levels
    as they are)."""
    black_world()
    plane("card", 2.0, mat=_image_material(_image("card", colour_space)))
    camera((0.0, 0.0, 50.0 / 18.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(64, 64))
    image = render_prism(fresh_scene, 16, max_bounces=1)
    decoded = _srgb_to_linear(LEVELS / 255.0) if colour_space == "sRGB" else LEVELS / 255.0
    for y in range(4):
        for x in range(4):
            rows = slice(64 - 16 * (y + 1) + 2, 64 - 16 * y - 2)  # pixel row 0 is at the top
            block = image[rows, 16 * x + 2:16 * (x + 1) - 2]
            assert block.mean(axis=(0, 1)) == pytest.approx(decoded[y, x], rel=0.02, abs=0.004), (x, y)
            assert block.std(axis=(0, 1)).max() < 0.01, (x, y)  # one texel, not a blend of two


COLOUR_SPACES = ["sRGB", "Non-Color", "Linear Rec.2020", "ACEScg", "Filmic Log", "AgX Log", "Display P3",
                 "Rec.1886"]


def test_every_colour_space_decodes_as_blender_does(prism_addon, fresh_scene):
    """One tile per input colour space Blender offers (8-bit images, plus a float image and bilinear
    interpolation): the tiles' colours within 2 % of Cycles', which decodes with the same OpenColorIO
    configuration."""
    black_world()
    tiles = []
    levels = np.array([[[60, 150, 210], [200, 120, 40]], [[90, 200, 110], [230, 230, 230]]], np.float64)
    images = [_image(space, space, 2, levels) for space in COLOUR_SPACES]
    images.append(_image("float", "Linear Rec.709", 2, levels, float_buffer=True))
    for index, image in enumerate(images):
        row, column = divmod(index, 3)
        tiles.append(plane(f"tile {index}", 0.95, location=(column - 1.0, 1.0 - row, 0.0),
                           mat=_image_material(image, "Linear")))
    camera((0.0, 0.0, 9.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(72, 72))
    ids = object_ids(fresh_scene, tiles)
    cycles = render_cycles(fresh_scene, 16, max_bounces=1)
    prism = render_prism(fresh_scene, 16, max_bounces=1)
    for index, image in enumerate(images):
        inside = ids == index
        assert inside.sum() >= 80, image.name
        for channel in range(3):
            assert prism[inside, channel].mean() == pytest.approx(cycles[inside, channel].mean(), rel=0.02,
                                                                 abs=0.003), (image.name, channel)
        assert (prism[inside] @ LUMINANCE).mean() == pytest.approx((cycles[inside] @ LUMINANCE).mean(), rel=0.02)
