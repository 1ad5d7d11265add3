"""Write the colorimetric tables a render reads (``engine/tracer/spectra/data/colorimetry.npz``).

Run by a developer when colour-science's tables change (the test ``tests/tracer/spectra/
test_colorimetry_tables.py`` fails then), not by Blender and not by a render:

    .venv/bin/python tools/generate_colorimetry_tables.py

The CIE 1931 2° colour-matching functions, CIE D65 and the BT.709 XYZ → RGB matrix, as colour-science
gives them (``spectra.colorimetry_tables.from_colour_science``), so that rendering does not import
colour-science (about half a second of every fresh process).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from engine.tracer.spectra import colorimetry_tables  # noqa: E402


def main() -> None:
    tables = colorimetry_tables.from_colour_science()
    colorimetry_tables.write(tables)
    path = colorimetry_tables.TABLES_PATH
    print(f"wrote {path} ({path.stat().st_size} bytes): CMFs {tables.cmf_nm[0]:.0f}-{tables.cmf_nm[-1]:.0f} nm, "
          f"D65 {tables.d65_nm[0]:.0f}-{tables.d65_nm[-1]:.0f} nm")


if __name__ == "__main__":
    main()
