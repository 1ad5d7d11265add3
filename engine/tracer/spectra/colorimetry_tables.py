"""The colorimetric tables every render needs, read from a file Prism ships instead of from colour-science.

Importing colour-science takes about half a second (it imports scipy.interpolate and its own modules),
and every render needed it for three tables only: the CIE 1931 2° colour-matching functions, CIE D65's
relative power and the BT.709 XYZ → RGB matrix. ``tools/generate_colorimetry_tables.py`` writes them
from colour-science (``from_colour_science``) into ``data/colorimetry.npz``; ``load`` reads that file
(about a millisecond), and ``tests/tracer/spectra/test_colorimetry_tables.py`` checks that the file still
equals what colour-science gives (the tabulated data bit for bit, the matrix, an inverse whose last bit depends
on the machine's LAPACK, to 1e-14). Renders that read a measured spectrum, an illuminant by
name or a colour checker still import colour-science for those.
"""

from __future__ import annotations

from collections import namedtuple
from pathlib import Path

import numpy as np

TABLES_PATH = Path(__file__).resolve().parent / "data" / "colorimetry.npz"

#: ``cmf_nm`` [M] (360-830 nm at 1 nm) and ``cmf_xyz`` [M, 3]: CIE 1931 2° observer; ``d65_nm`` [D]
#: (300-830 nm at 5 nm) and ``d65_power`` [D]: CIE D65 relative power (100 at 560 nm), from the daylight
#: basis at 6504 K; ``xyz_to_rec709`` [3, 3]: ITU-R BT.709 from its primaries and D65 white point.
ColorimetryTables = namedtuple("ColorimetryTables", "cmf_nm cmf_xyz d65_nm d65_power xyz_to_rec709")

_CACHE = {}


def from_colour_science() -> ColorimetryTables:
    """The tables as colour-science computes them (imports colour-science: for the generator and the test)."""
    from .cie import import_colour

    colour = import_colour()
    from colour.colorimetry import sd_CIE_illuminant_D_series
    from colour.temperature import CCT_to_xy_CIE_D

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    # D65's CCT is 6500 K on the pre-1968 c2 scale: 6500 * 1.4388 / 1.4380 = 6504 K.
    d65 = sd_CIE_illuminant_D_series(CCT_to_xy_CIE_D(6500.0 * 1.4388 / 1.4380))
    # The BT.709 matrix derived from its primaries and the D65 white point, so XYZ of that white maps to
    # (1, 1, 1) to double precision.
    matrix = colour.RGB_COLOURSPACES["ITU-R BT.709"].matrix_XYZ_to_RGB
    return ColorimetryTables(*(np.asarray(a, dtype=np.float64) for a in (
        cmfs.wavelengths, cmfs.values, d65.wavelengths, d65.values, matrix)))


def _checked(tables: ColorimetryTables) -> ColorimetryTables:
    # The interpolation in ``cie`` and ``rgb_to_spectrum`` indexes these tables directly by wavelength.
    if not np.allclose(np.diff(tables.cmf_nm), 1.0):
        raise RuntimeError(f"{TABLES_PATH.name}: the CIE 1931 table is expected at 1 nm steps.")
    if not np.allclose(np.diff(tables.d65_nm), 5.0):
        raise RuntimeError(f"{TABLES_PATH.name}: the D65 table is expected at 5 nm steps.")
    for table in tables:
        table.setflags(write=False)
    return tables


def load() -> ColorimetryTables:
    """The shipped tables (read once per process)."""
    if "tables" not in _CACHE:
        if not TABLES_PATH.exists():
            raise RuntimeError(f"Missing {TABLES_PATH.name}: run tools/generate_colorimetry_tables.py "
                               "(the file ships with Prism).")
        with np.load(TABLES_PATH) as data:
            _CACHE["tables"] = _checked(ColorimetryTables(*(np.array(data[name], dtype=np.float64)
                                                            for name in ColorimetryTables._fields)))
    return _CACHE["tables"]


def write(tables: ColorimetryTables, path: Path = TABLES_PATH) -> None:
    """Write ``tables`` (``from_colour_science()``) where ``load`` reads them."""
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez(path, **tables._asdict())
