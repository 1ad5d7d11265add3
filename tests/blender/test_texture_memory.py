"""Image textures in the memory check: an image that would not fit beside the frame is refused before
Prism reads its pixels, naming the image, its size, the estimate and the fix; the estimate per texel is
what reading an image really costs."""

from __future__ import annotations

import importlib
import tracemalloc
import types

import bpy
import pytest

from helpers.batch import run_batch
from helpers.bpy_scenes import build_lit_card_scene


def _module(prism_addon, name):
    return importlib.import_module(f"{prism_addon.__name__}.{name}")


def _textured_card(width, height, name="Poster"):
    """The lit card scene, the card's base colour from a generated ``width`` x ``height`` 8-bit image."""
    build_lit_card_scene(resolution=(8, 6))
    image = bpy.data.images.new(name, width, height)
    material = bpy.data.materials["Card material"]
    nodes = material.node_tree.nodes
    texture = nodes.new("ShaderNodeTexImage")
    texture.name, texture.image = "Poster texture", image
    material.node_tree.links.new(texture.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    return image


def test_an_image_that_does_not_fit_beside_the_frame_is_refused_before_its_pixels_are_read(
        prism_addon, fresh_scene, tmp_path, capsys, monkeypatch, bad_input):
    frames = _module(prism_addon, "engine.tracer.frame_plan")
    passes = _module(prism_addon, "engine.render.result_passes")
    _textured_card(64, 32)
    frame_bytes = passes.frame_plan(fresh_scene, None, 8, 6, region=None).needed_bytes
    # Room for the frame and 10 kB more: the 64 x 32 texture needs 64 * 32 * 24 = 49 kB while it is read.
    available = int((frame_bytes + 10_000) / frames.USABLE_FRACTION)
    monkeypatch.setattr(frames, "available_memory_bytes", lambda: available)
    read = []
    images = _module(prism_addon, "engine.export.nodes.images")
    levels = images._levels
    monkeypatch.setattr(images, "_levels", lambda pixels: read.append(pixels.shape) or levels(pixels))
    status, line = run_batch(capsys, "--samples", 1, "--output", tmp_path / "out.png")
    assert status == 1 and line.startswith(
        "Prism: error: Material 'Card material': the 'Poster texture' node's image 'Poster' (64 x 32, 8-bit) needs "
        "about 48 kB while Prism reads it (24 bytes a texel; 24 kB stay for the render) on top of the "), line
    assert line.endswith("scale the image down (Image Editor ▸ Image ▸ Resize, or a smaller file; e.g. 28 x 14 would "
                         "fit) or close other programs."), line
    assert not read, "no pixels are read"
    assert not (tmp_path / "out.png").exists()
    bad_input("an image texture that does not fit in the memory left beside the frame", status, line)


def test_the_estimate_of_large_textures(prism_addon):
    memory = _module(prism_addon, "engine.export.texture_memory")
    gb = memory.GB
    budget = memory.TextureBudget(available_bytes=8 * gb, reserved_bytes=1 * gb)
    budget.admit("Big", "Image Texture", 16384, 16384, memory.LEVELS)  # 6.0 GB while read, 3.0 GB kept
    assert budget.kept_bytes == 12 * 16384**2
    budget = memory.TextureBudget(available_bytes=8 * gb, reserved_bytes=1 * gb)
    with pytest.raises(memory.TextureMemoryError, match=r"image 'Huge' \(20000 x 20000, 8-bit\) needs about 8\.9 GB "
                       r"while Prism reads it \(24 bytes a texel; 4\.5 GB stay for the render\) on top of the 1\.0 GB"):
        budget.admit("Huge", "Image Texture", 20000, 20000, memory.LEVELS)
    with pytest.raises(memory.TextureMemoryError, match=r"\(20000 x 20000, float\) needs about 17\.9 GB"):
        budget.admit("Huge", "Image Texture", 20000, 20000, memory.FLOAT)
    assert budget.kept_bytes == 0  # a refused image is not counted


def _traced(measure):
    """``measure()``'s result, the peak of the memory it allocated and what stays allocated, in bytes as
    ``tracemalloc`` counts them (numpy reports its buffers to it). Counting allocations, not the resident set,
    keeps the figures exact however much freed memory the process already holds from earlier tests."""
    tracemalloc.start()
    try:
        result = measure()
        kept, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return result, peak, kept


@pytest.mark.parametrize("kind", ["LEVELS", "FLOAT"])
def test_reading_an_image_costs_what_the_estimate_says(prism_addon, fresh_scene, kind):
    memory = _module(prism_addon, "engine.export.texture_memory")
    images = _module(prism_addon, "engine.export.nodes.images")
    textures = _module(prism_addon, "engine.tracer.textures.image")
    node = types.SimpleNamespace(name="Image Texture", interpolation="Linear", extension="REPEAT")
    images.read_image(bpy.data.images.new("warm", 8, 8), node, lambda *_: None, {})  # OpenColorIO loaded once
    side = 1024
    image = bpy.data.images.new("measured", side, side, float_buffer=kind == "FLOAT")
    image.pixels[0]  # noqa: B018 - Blender's own buffer exists before the measurement

    def read():
        texture = images.read_image(image, node, lambda *_: None, {})
        return texture, textures.build_textures([texture])

    (texture, tables), peak, kept = _traced(read)
    cost = getattr(memory, kind)
    assert peak / side**2 == pytest.approx(max(cost.reading, cost.kept), rel=0.1)
    assert kept / side**2 == pytest.approx(cost.kept, rel=0.1)
    assert (texture.texels.nbytes + tables.bytes.nbytes + tables.floats.nbytes) / side**2 == pytest.approx(
        cost.kept, rel=0.1)
