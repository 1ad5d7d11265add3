"""Measured optical constants (n, k) of metals: Au, Ag, Cu (Johnson & Christy 1972) and Al (Rakić et al. 1998).

Data: ``data/conductors_nk.tsv`` (sources in its header), loaded lazily and
interpolated linearly in wavelength. Wavelengths outside a table are
evaluated at its nearest end (every table covers 360-830 nm).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import PrismInputError

DATA_PATH = Path(__file__).resolve().parent / "data" / "conductors_nk.tsv"
_TABLES = None  # {name: (wavelength_nm, n, k)}


def _tables():
    global _TABLES
    if _TABLES is None:
        rows = {}
        for line in DATA_PATH.read_text(encoding="utf-8").splitlines():
            if not line.strip() or line.startswith("#") or line.startswith("metal"):
                continue
            name, wl, n, k = line.split("\t")
            rows.setdefault(name, []).append((float(wl), float(n), float(k)))
        tables = {}
        for name, values in rows.items():
            arr = np.array(sorted(values))
            if not (np.all(np.diff(arr[:, 0]) > 0) and np.all(arr[:, 1] > 0) and np.all(arr[:, 2] >= 0)):
                raise RuntimeError(f"Conductor table for {name} in {DATA_PATH.name} is malformed.")
            tables[name] = (arr[:, 0].copy(), arr[:, 1].copy(), arr[:, 2].copy())
        _TABLES = tables
    return _TABLES


def conductor_names():
    """Names of the metals with measured data: ``["Au", "Ag", "Cu", "Al"]``."""
    return list(_tables())


def _lookup(name):
    tables = _tables()
    if name in tables:
        return tables[name]
    for key in tables:
        if str(name).strip().lower() == key.lower():
            return tables[key]
    raise PrismInputError(
        f"Unknown conductor '{name}': use one of {', '.join(tables)} "
        "(or leave the metal empty to use the base colour as reflectance)."
    )


def conductor_nk(name, wavelength_nm):
    """``(n, k)`` of metal ``name`` at ``wavelength_nm`` (any shape, float64 arrays of that shape)."""
    table_nm, n_table, k_table = _lookup(name)
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    if not np.all(np.isfinite(wavelength_nm)):
        raise PrismInputError(f"Conductor '{name}': wavelengths must be finite numbers in nm.")
    return np.interp(wavelength_nm, table_nm, n_table), np.interp(wavelength_nm, table_nm, k_table)


def conductor_range_nm(name):
    """(lo, hi) wavelength range of the measured table for ``name``."""
    table_nm = _lookup(name)[0]
    return float(table_nm[0]), float(table_nm[-1])
