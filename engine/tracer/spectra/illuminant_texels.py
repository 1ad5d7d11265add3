"""RGB texels of an emitting image (an HDRI) as illuminant spectra, millions at once.

Each texel becomes the spectrum an RGB emitter of its colour has (``rgb_to_spectrum.RGBEmission``):
s · S(λ) · D65(λ) / Y(D65) with s = 2 max(rgb) and S the Jakob-Hanika reflectance of rgb / s, whose
largest component is 1/2. Fitting S per texel (``reflectance_coefficients``) costs ~0.3 ms, far too
much for an image; but rgb / s always lies on one of three faces of the RGB cube scaled by 1/2 (the
largest component is 1/2, the two others in [0, 1/2]). Each face is tabulated once on a 65 x 65 grid
(``tools/generate_illuminant_faces.py`` → ``data/rec709_illuminant_faces.npy``), denser toward the
face's dark edges where the coefficients change fastest (grid coordinate sqrt(2 c)), and texels
interpolate it bilinearly: the Rec.709 round trip stays within 1.1e-4 of the 1/2-scaled colour
(2e-4 relative) for any colour.

Coefficients are stored over x = (λ - 360 nm) / 470 nm (values of order 10, well conditioned in
float32): S = 1/2 + U / (2 sqrt(1 + U²)), U = a x² + b x + c.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..jit import kernel
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

FACES_PATH = Path(__file__).resolve().parent / "data" / "rec709_illuminant_faces.npy"
FACE_SIZE = 65
_SPAN_NM = VISIBLE_MAX_NM - VISIBLE_MIN_NM
_CACHE = {}


def generate_faces(size: int = FACE_SIZE) -> np.ndarray:
    """Unit-domain coefficients [3, size, size, 3]: face f has component f at 1/2 and the other two
    (in order) at grid coordinates g_i = (i / (size - 1))² / 2."""
    from .rgb_to_spectrum import _to_unit_domain, reflectance_coefficients

    grid = 0.5 * np.linspace(0.0, 1.0, size) ** 2
    a, b = np.meshgrid(grid, grid, indexing="ij")
    faces = np.zeros((3, size, size, 3))
    for face in range(3):
        others = [c for c in range(3) if c != face]
        rgb = np.zeros((size, size, 3))
        rgb[..., face] = 0.5
        rgb[..., others[0]] = a
        rgb[..., others[1]] = b
        faces[face] = _to_unit_domain(reflectance_coefficients(rgb.reshape(-1, 3))).reshape(size, size, 3)
    if not np.isfinite(faces).all():
        raise RuntimeError("A face of the illuminant table has non-finite coefficients.")
    return faces


def _faces() -> np.ndarray:
    if "faces" not in _CACHE:
        if not FACES_PATH.exists():
            raise RuntimeError(f"Missing {FACES_PATH.name}: run tools/generate_illuminant_faces.py (it ships with Prism).")
        _CACHE["faces"] = np.load(FACES_PATH)
    return _CACHE["faces"]


def d65_normalisation() -> float:
    """Y of the relative D65 spectrum (``RGBEmission``'s divisor)."""
    from . import rgb_to_spectrum

    rgb_to_spectrum._integration()
    return float(rgb_to_spectrum._CACHE["d65_y"])


def illuminant_texels(rgb) -> np.ndarray:
    """float32 [..., 4] (a, b, c, scale) for linear Rec.709 colours ``rgb`` [..., 3] (negative and
    non-finite components count as 0): the texel's spectrum is scale · S(x; a, b, c) · D65(λ)."""
    rgb = np.nan_to_num(np.asarray(rgb, np.float64), nan=0.0, posinf=0.0, neginf=0.0)
    rgb = np.maximum(rgb, 0.0)
    shape = rgb.shape[:-1]
    flat = rgb.reshape(-1, 3)
    faces = _faces()
    size = faces.shape[1]
    out = np.zeros((len(flat), 4), np.float64)
    largest = flat.max(axis=1)
    face = flat.argmax(axis=1)
    lit = largest > 0.0
    for f in range(3):
        chosen = np.flatnonzero(lit & (face == f))
        if chosen.size == 0:
            continue
        others = [c for c in range(3) if c != f]
        # Grid coordinate of component c/(2 max): sqrt(2 · c / (2 max)) (size - 1).
        gi = np.sqrt(np.clip(flat[chosen, others[0]] / largest[chosen], 0.0, 1.0)) * (size - 1)
        gj = np.sqrt(np.clip(flat[chosen, others[1]] / largest[chosen], 0.0, 1.0)) * (size - 1)
        i0 = np.minimum(gi.astype(np.int64), size - 2)
        j0 = np.minimum(gj.astype(np.int64), size - 2)
        fi = (gi - i0)[:, None]
        fj = (gj - j0)[:, None]
        table = faces[f]
        out[chosen, :3] = ((1 - fi) * (1 - fj) * table[i0, j0] + fi * (1 - fj) * table[i0 + 1, j0]
                           + (1 - fi) * fj * table[i0, j0 + 1] + fi * fj * table[i0 + 1, j0 + 1])
    out[:, 3] = 2.0 * largest / d65_normalisation()
    return out.reshape(shape + (4,)).astype(np.float32)


@kernel
def texel_reflectance(a, b, c, wavelength_nm):
    """S(λ) of unit-domain coefficients (a, b, c)."""
    x = (wavelength_nm - VISIBLE_MIN_NM) / _SPAN_NM
    u = (a * x + b) * x + c
    return 0.5 + 0.5 * u / math.sqrt(1.0 + u * u)
