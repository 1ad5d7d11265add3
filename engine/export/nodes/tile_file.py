"""A UDIM tile read with OpenImageIO (the library Blender bundles): from the tile's own file, or from the
bytes Blender packed into the .blend for it, written to a temporary file first (OpenImageIO's Python
binding reads files, not memory buffers).

Pixels are handed on as Blender's ``Image.pixels`` gives them (row 0 at the bottom), so a tile is decoded
exactly as an ordinary image in the UDIM image's colour space, whichever way its bytes reach Prism: 8-bit
files as levels / 255 with straight alpha, decoded later; deeper files (half and float EXR, HDR, 16-bit
PNG and TIFF) as Blender loads them into float buffers, decoded here from the image's colour space to
scene-linear (Cycles decodes them too: a float tile in 'sRGB' is not taken as linear).
"""

from __future__ import annotations

import os

import numpy as np

from ...output.openimageio import import_openimageio
from .colour_spaces import RAW_SPACES, to_linear
from .pixel_source import PixelSource

#: Formats Blender loads into 8-bit buffers; it loads every deeper one into a float buffer.
_BYTE_FORMATS = ("uint8", "int8")


def _open(oiio, path):
    config = oiio.ImageSpec()
    config.attribute("oiio:UnassociatedAlpha", 1)  # straight alpha, as Blender keeps 8-bit images
    return oiio.ImageInput.open(path, config)


def file_source(path, name, colour_space, alpha_mode):
    """A ``PixelSource`` for the image file at ``path``, or None when OpenImageIO cannot open it.

    The file is opened here for its size and format and again when the pixels are read, each time closed
    at once: nothing stays open if the texels are never read (a texture over the memory budget), so a
    temporary copy can always be deleted."""
    oiio = import_openimageio()
    reader = _open(oiio, path)
    if reader is None:
        return None
    spec = reader.spec()
    reader.close()
    width, height, channels = spec.width, spec.height, spec.nchannels
    is_float = str(spec.format) not in _BYTE_FORMATS

    def fill(out):
        reader = _open(oiio, path)
        if reader is None:
            raise OSError(f"OpenImageIO could not reopen '{path}'")
        try:
            pixels = reader.read_image(0, 0, 0, min(channels, 4), "float")
        finally:
            reader.close()
        if pixels is None:
            raise OSError(f"OpenImageIO could not read '{path}'")
        pixels = np.asarray(pixels, np.float32).reshape(height, width, -1)[::-1]  # files store the top row first
        rgba = out.reshape(height, width, 4)
        if pixels.shape[2] < 3:  # grey, or grey and alpha
            rgba[..., :3] = pixels[..., :1]
            rgba[..., 3] = pixels[..., 1] if pixels.shape[2] == 2 else 1.0
        else:
            rgba[..., :3] = pixels[..., :3]
            rgba[..., 3] = pixels[..., 3] if pixels.shape[2] == 4 else 1.0
        if is_float and colour_space not in RAW_SPACES:  # Blender makes a float buffer scene-linear on load
            linear = to_linear(colour_space, rgba[..., :3].reshape(-1, 3))
            if linear is not None:  # a colour space Prism cannot decode: the values as stored
                rgba[..., :3] = linear.reshape(height, width, 3)

    return PixelSource(name, width, height, is_float, colour_space, alpha_mode, fill)


def packed_source(packed, folder, name, colour_space, alpha_mode):
    """A ``PixelSource`` for the packed file ``packed`` (an ``ImagePackedFile``), its bytes written into
    ``folder`` (which the caller deletes once the pixels are read), or None when they cannot be decoded.
    The copy keeps the packed file's extension: OpenImageIO recognises most formats by their bytes, but
    tries the extension's format first."""
    extension = os.path.splitext(packed.filepath)[1]
    path = os.path.join(folder, f"tile{packed.tile_number}{extension}")
    with open(path, "wb") as copy:
        copy.write(packed.packed_file.data)
    return file_source(path, name, colour_space, alpha_mode)
