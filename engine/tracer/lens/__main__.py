"""``python -m engine.tracer.lens FILE [--wavelength NM] [--focus-distance MM] [--fstop N]``

Prints a lens's first-order data as JSON: paraxial properties, the film distance for
infinity (and for the focus distance, measured from the film), the field of view on a
36 mm sensor, the axial colour between 486 and 656 nm, and the loader's notes (assumed
glasses). A bad file or argument prints one message on stderr and exits with status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import traceback

from ..errors import PrismInputError
from ..spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM
from .catalogue import DEFAULT_SENSOR_WIDTH_MM, lens_report
from .media import D_LINE_NM

#: No lens in air is faster than f/0.5 (the numerical aperture cannot exceed 1).
FASTEST_FSTOP = 0.5
SLOWEST_FSTOP = 1024.0
#: Wider than any film or sensor format (8x10 inch sheet film is 254 mm wide).
MAX_SENSOR_WIDTH_MM = 500.0


def _number_within(name: str, low: float, high: float, unit: str, hint: str = ""):
    """An argparse type: a finite number in [low, high], refused with the range and a hint."""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number (got '{text}')") from None
        if not (math.isfinite(value) and low <= value <= high):
            within = f"{low:g} and {high:g}" + (f" {unit}" if unit else "")
            raise argparse.ArgumentTypeError(f"{name} must be between {within} (got {text}){hint}")
        return value

    return parse


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
    parser.add_argument("--wavelength", default=D_LINE_NM, metavar="NM",
                        type=_number_within("the wavelength", VISIBLE_MIN_NM, VISIBLE_MAX_NM, "nm",
                                            ", the range Prism renders"),
                        help="wavelength for the paraxial data and focus (default: d line, 587.56 nm)")
    parser.add_argument("--focus-distance", default=None, metavar="MM",
                        type=_number_within("the focus distance", 1e-3, 1e12, "mm",
                                            "; leave it out to focus at infinity"),
                        help="object distance from the film, mm (default: infinity only)")
    parser.add_argument("--fstop", default=None, metavar="N",
                        type=_number_within("the f-stop", FASTEST_FSTOP, SLOWEST_FSTOP, "",
                                            "; no lens in air is faster than f/0.5"),
                        help="stop the lens to f/N")
    parser.add_argument("--sensor-width", default=DEFAULT_SENSOR_WIDTH_MM, metavar="MM",
                        type=_number_within("the sensor width", 1e-3, MAX_SENSOR_WIDTH_MM, "mm"),
                        help="sensor width for the field of view (default: 36 mm, Blender's)")
    args = parser.parse_args(argv)
    try:
        report = lens_report(args.file, args.wavelength, args.focus_distance, args.fstop, args.sensor_width)
    except PrismInputError as error:
        print(f"prism lens: error: {error}", file=sys.stderr)
        return 2
    except Exception as error:  # noqa: BLE001 - a bug: the traceback, then one line saying so
        traceback.print_exc()
        print(f"prism lens: error: unexpected {type(error).__name__} (a bug in Prism; please report it with the "
              f"traceback above): {error}", file=sys.stderr)
        return 1
    json.dump(_clean(report), sys.stdout, indent=2)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
