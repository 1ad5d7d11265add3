"""Generate the RGB → illuminant-coefficient face table that HDRI texels are interpolated from.

Run once by a developer (not by Blender, not by a render):

    .venv/bin/python tools/generate_illuminant_faces.py

Fits the Jakob-Hanika coefficients of every grid colour with ``rgb_to_spectrum`` (about 5 s) and writes
``engine/tracer/spectra/data/rec709_illuminant_faces.npy``, then reports the round-trip error of the
interpolation on random colours (see ``engine/tracer/spectra/illuminant_texels.py``).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from engine.tracer.spectra import illuminant_texels, rgb_to_spectrum  # noqa: E402


def main() -> None:
    faces = illuminant_texels.generate_faces()
    np.save(illuminant_texels.FACES_PATH, faces)
    illuminant_texels._CACHE.clear()
    rng = np.random.default_rng(1)
    rgb = rng.random((20000, 3)) ** 2
    texels = illuminant_texels.illuminant_texels(rgb).astype(np.float64)
    base = rgb / (2.0 * rgb.max(axis=1, keepdims=True))
    error = rgb_to_spectrum._residual_norm(texels[:, :3], base * rgb_to_spectrum.white_rgb())
    print(f"wrote {illuminant_texels.FACES_PATH.name}: round trip on 1/2-scaled colours, "
          f"median {np.median(error):.2e}, max {error.max():.2e}")


if __name__ == "__main__":
    main()
