"""The multispectral EXR: a render's band radiance in the layout of Fichet, Pacanowski and Wilkie,
"An OpenEXR Layout for Spectral Images" (JCGT 10(3), 2021), written by colour-science.

Channels ``S0.<centre>nm`` (the emissive Stokes component: no polarisation) hold each band's mean
spectral radiance per nanometre, bands tiling 360-830 nm (``tracer.spectral_film``); a reader assumes
box responses between consecutive centres, which is what they are. ``R``, ``G``, ``B`` hold the render's
own scene-linear Rec.709 image, so any EXR viewer shows the file. Radiance is in Prism's scene units:
integrated against ȳ / ∫ȳ (CIE 1931) it gives the luminance of the RGB image.

The file is written whole or not at all (a temporary file, then one rename).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..batch.output_files import atomic_output, check_writable as _check_output_writable
from .openimageio import import_openimageio

UNITS_ATTRIBUTE = "prism:spectralRadiance"
UNITS_TEXT = "per nm, scene-linear; integrated against CIE 1931 ybar / (integral of ybar) it gives the luminance Y"


def requested_path(scene, request, preview: bool) -> Path | None:
    """Where this render's spectral EXR goes: the request's path (batch ``--spectral-output``), else the
    scene's Render ▸ Prism ▸ Spectral Output file (``#`` → the frame number) when it is on; None for
    previews, sample chunks (``--chunk-seed``) and when nothing asks for it."""
    if request.spectral_output:
        return Path(request.spectral_output)
    prism = scene.prism
    if preview or request.keep_film or not prism.use_spectral_output:
        return None  # a chunk of a render holds some of its samples: its spectra are not the render's
    import bpy

    from ..batch.output_files import numbered_output

    return numbered_output(Path(bpy.path.abspath(prism.spectral_output_path) or "spectral.exr"), scene.frame_current)


def check_writable(path) -> None:
    """``PrismInputError`` now, before a render, when the spectral EXR could not be written to ``path``."""
    from ..tracer.errors import PrismInputError

    try:
        _check_output_writable(Path(path))
    except PrismInputError as error:
        raise PrismInputError(f"Spectral output (Render ▸ Prism ▸ Spectral Output, or --spectral-output): {error}") from None


def write_spectral_exr(path, centres_nm, bands, rgb) -> Path:
    """Write ``bands`` float [H, W, B] (row 0 = top) at band centres ``centres_nm`` [B] and the preview
    ``rgb`` [H, W, 3] to ``path`` (float32 EXR); returns the path."""
    oiio = import_openimageio()
    from ..tracer.spectra.cie import import_colour

    colour = import_colour()
    io = colour.io
    primaries = colour.RGB_COLOURSPACES["ITU-R BT.709"]
    chromaticities = np.ravel(np.vstack([primaries.primaries, primaries.whitepoint])).tolist()
    attributes = [
        io.Image_Specification_Attribute("spectralLayoutVersion", "1.0"),
        io.Image_Specification_Attribute("emissiveUnits", "W.m^-2.sr^-1"),
        io.Image_Specification_Attribute(UNITS_ATTRIBUTE, UNITS_TEXT),
        io.Image_Specification_Attribute("chromaticities", chromaticities, oiio.TypeDesc("float[8]")),
    ]
    specification = io.Specification_Fichet2021(is_emissive=True, attributes=attributes)
    components = {"S0": (np.asarray(centres_nm, np.float64), np.asarray(bands, np.float32))}
    preview = np.asarray(rgb, np.float32)
    path = Path(path)
    with atomic_output(path) as temporary:
        io.write_spectral_image_Fichet2021(components, str(temporary), "float32", specification,
                                           components_to_RGB_callable=lambda *_: (preview, []))
    return path
