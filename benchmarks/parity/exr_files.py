"""Reading the EXR files Blender wrote back as scene-linear RGBA arrays [H, W, 4], row 0 on top; several
layers or frames are put side by side (left to right in their order) so one picture and one mean cover
them all."""

from __future__ import annotations

import importlib

import bpy
import numpy as np


def read_still(path) -> np.ndarray:
    """An RGBA EXR as Blender loads it (float32)."""
    image = bpy.data.images.load(str(path))
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1]


def read_frames(paths) -> np.ndarray:
    """The frames' images side by side (the files sorted by frame number)."""
    if not paths:
        raise FileNotFoundError("the animation render wrote no frame")
    return np.concatenate([read_still(path) for path in paths], axis=1)


def read_layers(path, layer_names) -> np.ndarray:
    """Each view layer's Combined pass of a multilayer EXR, side by side in ``layer_names``' order.
    Blender's image loader shows one layer only, so the file is read with OpenImageIO (bundled)."""
    from render import prism_package_name

    openimageio = importlib.import_module(f"{prism_package_name()}.engine.output.openimageio").import_openimageio()
    buffer = openimageio.ImageBuf(str(path))
    spec = buffer.spec()
    pixels = np.asarray(buffer.get_pixels(openimageio.FLOAT)).reshape(spec.height, spec.width, spec.nchannels)
    channels = list(spec.channelnames)
    images = []
    for name in layer_names:
        # Blender names a layer's channels "<layer>.Combined.R" (one view: no view part).
        indices = [channels.index(f"{name}.Combined.{c}") for c in "RGBA"]
        images.append(pixels[..., indices])
    return np.concatenate(images, axis=1)
