"""Generate the Jakob & Hanika (2019) RGB -> reflectance coefficient table for Prism.

Run once by a developer (not by Blender, not by a render):

    .venv/bin/python tools/generate_upsampling_table.py --size 8 --step 5

It optimises the table with colour-science's ``LUT3D_Jakob2019`` for linear
Rec.709 (ITU-R BT.709 primaries, D65) over 360-830 nm and writes
``engine/tracer/spectra/data/rec709_jakob2019.coeff`` (colour's/the paper's ``.coeff``
format, float32). ``engine/tracer/spectra/rgb_to_spectrum.py`` loads it lazily and
polishes each looked-up colour with a few Levenberg-Marquardt steps, so a small
table is enough. colour takes about 0.08 s per table cell on one unloaded core,
so a size-N table costs about 3·N³ × 0.08 s (size 8: 2 min); see docs/colour.md
for the round-trip error of each size.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "engine" / "tracer" / "data" / "rec709_jakob2019.coeff"


def d65_spectral_distribution(shape):
    """The D65 spectrum the tracer uses (``rgb_to_spectrum._d65_table``), as colour data aligned to ``shape``."""
    import colour

    sys.path.insert(0, str(ROOT))
    from engine.tracer.spectra.rgb_to_spectrum import _d65_table

    wavelength_nm, power = _d65_table()
    return colour.SpectralDistribution(power, wavelength_nm).align(shape)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=8, help="table resolution per axis")
    parser.add_argument("--step", type=float, default=10.0, help="spectral sampling step in nm")
    parser.add_argument("--output", type=Path, default=OUTPUT)
    args = parser.parse_args(argv)

    os.environ.setdefault("OMP_NUM_THREADS", "1")
    warnings.filterwarnings("ignore")
    import colour
    from colour.recovery import LUT3D_Jakob2019

    shape = colour.SpectralShape(360.0, 830.0, args.step)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    illuminant = d65_spectral_distribution(shape)
    space = colour.RGB_COLOURSPACES["ITU-R BT.709"]

    start = time.perf_counter()
    lut = LUT3D_Jakob2019()
    lut.generate(space, cmfs, illuminant, args.size, lambda *a, **k: None)
    seconds = time.perf_counter() - start
    args.output.parent.mkdir(parents=True, exist_ok=True)
    lut.write(args.output)
    print(
        f"size {args.size}, step {args.step} nm: {3 * args.size**3} optimisations in {seconds:.1f} s; "
        f"wrote {args.output} ({args.output.stat().st_size} bytes)"
    )


if __name__ == "__main__":
    main()
