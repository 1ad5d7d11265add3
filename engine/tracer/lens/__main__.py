"""``python -m engine.tracer.lens FILE [--wavelength NM] [--focus-distance MM] [--fstop N]``

Prints a lens's first-order data as JSON: paraxial properties, the film distance for
infinity (and for the focus distance, measured from the film), the field of view on a
36 mm sensor, the axial colour between 486 and 656 nm, and the loader's notes (assumed
glasses). A bad file prints one message on stderr and exits with status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from ..errors import PrismInputError
from .catalogue import DEFAULT_SENSOR_WIDTH_MM, lens_report
from .media import D_LINE_NM


def _clean(value):
    """JSON has no inf/NaN: write them as null."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m engine.tracer.lens", description=__doc__.splitlines()[2])
    parser.add_argument("file", help="lens prescription: Prism .lens or pbrt/CS184 .dat")
    parser.add_argument("--wavelength", type=float, default=D_LINE_NM, metavar="NM",
                        help="wavelength for the paraxial data and focus (default: d line, 587.56 nm)")
    parser.add_argument("--focus-distance", type=float, default=None, metavar="MM",
                        help="object distance from the film, mm (default: infinity only)")
    parser.add_argument("--fstop", type=float, default=None, metavar="N", help="stop the lens to f/N")
    parser.add_argument("--sensor-width", type=float, default=DEFAULT_SENSOR_WIDTH_MM, metavar="MM",
                        help="sensor width for the field of view (default: 36 mm, Blender's)")
    args = parser.parse_args(argv)
    try:
        report = lens_report(args.file, args.wavelength, args.focus_distance, args.fstop, args.sensor_width)
    except PrismInputError as error:
        print(f"prism lens: error: {error}", file=sys.stderr)
        return 2
    json.dump(_clean(report), sys.stdout, indent=2)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
