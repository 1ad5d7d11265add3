"""Generate the dense RGB -> sigmoid-coefficient table the kernels upsample per-hit colours with.

Run once by a developer (not by Blender, not by a render):

    .venv/bin/python tools/generate_rgb_lut.py            # about 40 s

Colours computed per hit (textures, node math) become reflectance spectra in the kernels by trilinear
interpolation of Jakob-Hanika coefficients in this table (``spectra.rgb_lut``). Every grid colour is
fitted exactly as constant colours are (``rgb_to_spectrum.reflectance_coefficients``: a first
guess, here from the small committed table (``jakob_start``), plus Levenberg-Marquardt polish), so
constant and textured colours share one upsampling. Grid: for the largest channel c, its value z (a
smoothstep-of-smoothstep grid, dense near 0 and 1, as Jakob and Hanika use) and the ratios of the next two channels x = rgb[c+1]/z, y = rgb[c+2]/z
(uniform). Stored as float32 coefficients of x = (λ - 360) / 470 (well conditioned), [3, N, N, N, 3].
Size 32 round-trips colours within 0.7 % (99 % within 0.35 %).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from engine.tracer.spectra import rgb_lut, rgb_to_spectrum  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=rgb_lut.LUT_SIZE)
    parser.add_argument("--output", type=Path, default=rgb_lut.LUT_PATH)
    args = parser.parse_args(argv)
    n = args.size
    z_grid, ratio_grid = rgb_lut.grid(n)
    channel, z, y, x = np.meshgrid(np.arange(3), z_grid, ratio_grid, ratio_grid, indexing="ij")
    rgb = np.zeros(channel.shape + (3,))
    for c in range(3):
        m = channel == c
        rgb[m, c] = z[m]
        rgb[m, (c + 1) % 3] = (x * z)[m]
        rgb[m, (c + 2) % 3] = (y * z)[m]
    flat = rgb.reshape(-1, 3)
    coefficients = np.empty_like(flat)
    started = time.perf_counter()
    for s in range(0, len(flat), 8192):
        # First guesses from colour-science's Jakob-Hanika table: the table being made is the default's.
        coefficients[s:s + 8192] = rgb_to_spectrum.reflectance_coefficients(flat[s:s + 8192],
                                                                            start=rgb_to_spectrum.jakob_start)
    unit = rgb_to_spectrum._to_unit_domain(coefficients).astype(np.float32).reshape(channel.shape + (3,))
    args.output.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(args.output, coefficients=unit, z_grid=z_grid)
    print(f"size {n}: {len(flat)} fits in {time.perf_counter() - started:.1f} s; wrote {args.output} "
          f"({args.output.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
