"""Optical glasses: catalogue Sellmeier glasses, Abbe-number glasses and constant indices.

``Glass.index(wavelength_nm)`` is the refractive index (float64, broadcast).
Catalogue glasses (``data/glasses.tsv``: SCHOTT/OHARA via refractiveindex.info,
fused silica from Malitson 1965) use the three-term Sellmeier formula and are
checked when the catalogue is first loaded (finite, > 1, strictly decreasing
over 360-830 nm within their valid range, n_d/V_d matching the catalogue).

Outside a glass's valid range (e.g. SF11 below 390 nm) the index is evaluated
at the nearest edge of the range instead of extrapolating towards the Sellmeier
pole; the first time this happens for a glass in a process a ``warnings.warn``
names the glass and range, and each ``Glass`` instance counts the clamped
samples in ``out_of_range_count`` (for the render stats).

``glass_from_abbe(n_d, v_d)`` builds a Cauchy glass n(λ) = A + B / λ² fitted
exactly to n_d and V_d:

    n_F - n_C = B (1/λ_F² - 1/λ_C²) = (n_d - 1) / V_d
    =>  B = (n_d - 1) / (V_d (1/λ_F² - 1/λ_C²)),   A = n_d - B / λ_d²

with λ_d = 587.5618 nm, λ_F = 486.1327 nm, λ_C = 656.2725 nm.
"""

from __future__ import annotations

import difflib
import math
import threading
import warnings
from pathlib import Path

import numpy as np

from ..errors import PrismInputError, UnknownGlassError
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM, VISIBLE_NM_GRID

LAMBDA_D_NM = 587.5618
LAMBDA_F_NM = 486.1327
LAMBDA_C_NM = 656.2725

CATALOGUE_PATH = Path(__file__).resolve().parent / "data" / "glasses.tsv"

_CATALOGUE = None  # {normalised name: (SellmeierGlass, catalogue_nd, catalogue_vd)}
_WARNED = set()
_WARN_LOCK = threading.Lock()


def _key(name):
    return "".join(ch for ch in str(name).lower() if ch not in " -_")


class Glass:
    """A refractive medium. Subclasses define ``_raw_index(wavelength_nm)``.

    ``name``; ``index(wavelength_nm)``; ``n_d``, ``v_d`` (computed at the d, F,
    C lines); ``valid_range_nm`` (lo, hi); ``is_dispersive``;
    ``out_of_range_count`` (samples evaluated at the edge of the valid range).
    """

    is_dispersive = True

    def __init__(self, name, valid_range_nm):
        self.name = name
        self.valid_range_nm = (float(valid_range_nm[0]), float(valid_range_nm[1]))
        self.out_of_range_count = 0
        self._count_lock = threading.Lock()

    def __repr__(self):
        return f"{type(self).__name__}({self.name!r}, n_d={self.n_d:.5f}, v_d={self.v_d:.2f})"

    def _raw_index(self, wavelength_nm):
        raise NotImplementedError

    def index(self, wavelength_nm):
        """Refractive index at ``wavelength_nm`` (any shape, float64); clamps outside the valid range."""
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        lo, hi = self.valid_range_nm
        outside = ~((wavelength_nm >= lo) & (wavelength_nm <= hi))
        if outside.any():
            self._report_out_of_range(wavelength_nm, outside)
            wavelength_nm = np.clip(wavelength_nm, lo, hi)  # NaN stays NaN and is counted
        return self._raw_index(wavelength_nm)

    def _report_out_of_range(self, wavelength_nm, outside):
        count = int(np.count_nonzero(outside))
        with self._count_lock:
            self.out_of_range_count += count
        with _WARN_LOCK:
            if self.name in _WARNED:
                return
            _WARNED.add(self.name)
        lo, hi = self.valid_range_nm
        bad = wavelength_nm[outside]
        finite = bad[np.isfinite(bad)]
        seen = f"{finite.min():g}–{finite.max():g} nm" if finite.size else "NaN"
        warnings.warn(
            f"Glass '{self.name}' is only specified for {lo:g}–{hi:g} nm but was sampled at {seen}; "
            "those wavelengths use the index at the nearest edge of the range (reported once per glass).",
            RuntimeWarning,
            stacklevel=3,
        )

    @property
    def n_d(self):
        """Index at the helium d line, 587.5618 nm."""
        return float(self._raw_index(np.float64(LAMBDA_D_NM)))

    @property
    def v_d(self):
        """Abbe number (n_d - 1) / (n_F - n_C); infinite for a non-dispersive glass."""
        dn = float(self._raw_index(np.float64(LAMBDA_F_NM)) - self._raw_index(np.float64(LAMBDA_C_NM)))
        return math.inf if dn == 0.0 else (self.n_d - 1.0) / dn


class SellmeierGlass(Glass):
    """Three-term Sellmeier glass: n² = 1 + Σ B_i λ² / (λ² - C_i), λ in µm, C_i in µm²."""

    def __init__(self, name, b, c_um2, valid_range_nm, source=""):
        super().__init__(name, valid_range_nm)
        self.b = np.asarray(b, dtype=np.float64)
        self.c_um2 = np.asarray(c_um2, dtype=np.float64)
        self.source = source

    def _raw_index(self, wavelength_nm):
        l2 = (np.asarray(wavelength_nm, dtype=np.float64) * 1e-3) ** 2
        n2 = 1.0
        for b, c in zip(self.b, self.c_um2):  # three terms
            n2 = n2 + b * l2 / (l2 - c)
        return np.sqrt(n2)


class CauchyGlass(Glass):
    """n(λ) = A + B / λ² (λ in nm, B in nm²), valid over the visible range."""

    def __init__(self, name, a, b_nm2):
        super().__init__(name, (VISIBLE_MIN_NM, VISIBLE_MAX_NM))
        self.a = float(a)
        self.b_nm2 = float(b_nm2)

    def _raw_index(self, wavelength_nm):
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        return self.a + self.b_nm2 / wavelength_nm**2


class ConstantGlass(Glass):
    """A non-dispersive medium of index ``ior`` at every wavelength."""

    is_dispersive = False

    def __init__(self, ior, name=None):
        super().__init__(name or f"IOR {ior:g}", (0.0, math.inf))
        self.ior = float(ior)

    def _raw_index(self, wavelength_nm):
        return np.full(np.shape(wavelength_nm), self.ior)

    def index(self, wavelength_nm):
        """``ior`` broadcast to the shape of ``wavelength_nm``."""
        return np.full(np.shape(wavelength_nm), self.ior)


def _validate_dispersion(glass, what):
    """Finite, > 1 and strictly decreasing over 360-830 nm (within the valid range)."""
    lo = max(VISIBLE_MIN_NM, glass.valid_range_nm[0])
    hi = min(VISIBLE_MAX_NM, glass.valid_range_nm[1])
    with np.errstate(all="ignore"):  # a pole in range shows up as inf/NaN, reported below
        n = glass._raw_index(np.linspace(lo, hi, len(VISIBLE_NM_GRID)))
    if not (np.all(np.isfinite(n)) and np.all(n > 1.0) and np.all(np.diff(n) < 0.0)):
        raise PrismInputError(
            f"{what}: its refractive index is not finite, above 1 and decreasing over {lo:g}–{hi:g} nm; "
            "check the dispersion data."
        )


def _catalogue():
    global _CATALOGUE
    if _CATALOGUE is None:
        entries = {}
        header = None
        for line in CATALOGUE_PATH.read_text(encoding="utf-8").splitlines():
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.split("\t")
            if header is None:
                header = fields
                continue
            row = dict(zip(header, fields))
            glass = SellmeierGlass(
                row["name"],
                [float(row[k]) for k in ("B1", "B2", "B3")],
                [float(row[k]) for k in ("C1_um2", "C2_um2", "C3_um2")],
                (float(row["valid_min_nm"]), float(row["valid_max_nm"])),
                row["source"],
            )
            _validate_dispersion(glass, f"Catalogue glass '{glass.name}'")
            entries[_key(row["name"])] = (glass, float(row["catalogue_nd"]), float(row["catalogue_vd"]))
        _CATALOGUE = entries
    return _CATALOGUE


def glass_names():
    """Names of the catalogue glasses, in catalogue order."""
    return [glass.name for glass, _, _ in _catalogue().values()]


def catalogue_values(name):
    """The catalogue's published (n_d, V_d) of a catalogue glass (for checks)."""
    _, nd, vd = _catalogue()[_key(glass_by_name(name).name)]
    return nd, vd


def glass_by_name(name):
    """A new ``Glass`` for catalogue glass ``name`` (case, spaces, '-' and '_' ignored).

    Unknown names raise ``UnknownGlassError`` listing close matches and all names.
    """
    entry = _catalogue().get(_key(name))
    if entry is None:
        names = glass_names()
        close = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        close += [n for n in names if _key(name) and _key(name) in _key(n) and n not in close]
        hint = f" Did you mean {', '.join(close)}?" if close else ""
        raise UnknownGlassError(
            f"Unknown glass '{name}'.{hint} Catalogue glasses: {', '.join(names)}; "
            "or give n_d and V_d (Abbe number) instead."
        )
    glass = entry[0]
    return SellmeierGlass(glass.name, glass.b, glass.c_um2, glass.valid_range_nm, glass.source)


def _check_nd_vd(n_d, v_d):
    try:
        n_d, v_d = float(n_d), float(v_d)
    except (TypeError, ValueError):
        raise PrismInputError(f"Glass n_d and V_d must be numbers (got {n_d!r}, {v_d!r}).") from None
    if not (math.isfinite(n_d) and n_d > 1.0):
        raise PrismInputError(f"Glass n_d {n_d:g} is invalid: the refractive index must be a finite number above 1.")
    if not (math.isfinite(v_d) and v_d > 0.0):
        raise PrismInputError(f"Glass Abbe number V_d {v_d:g} is invalid: it must be a finite number above 0.")
    return n_d, v_d


def glass_from_abbe(n_d, v_d):
    """Cauchy glass n = A + B/λ² with exactly this n_d and Abbe number V_d (see module docstring)."""
    n_d, v_d = _check_nd_vd(n_d, v_d)
    b_nm2 = (n_d - 1.0) / (v_d * (1.0 / LAMBDA_F_NM**2 - 1.0 / LAMBDA_C_NM**2))
    a = n_d - b_nm2 / LAMBDA_D_NM**2
    glass = CauchyGlass(f"n_d={n_d:g} V_d={v_d:g}", a, b_nm2)
    _validate_dispersion(
        glass, f"Glass n_d={n_d:g}, V_d={v_d:g} (so much dispersion that n drops below 1 in 360–830 nm; raise V_d)"
    )
    return glass


def constant_ior(n):
    """A non-dispersive medium of index ``n`` (finite, > 0; below 1 is allowed, e.g. an air bubble in water)."""
    try:
        n = float(n)
    except (TypeError, ValueError):
        raise PrismInputError(f"IOR must be a number (got {n!r}).") from None
    if not (math.isfinite(n) and n > 0.0):
        raise PrismInputError(f"IOR {n:g} is invalid: use a finite index above 0 (glass is about 1.5).")
    return ConstantGlass(n)


def nearest_catalogue_glass(n_d, v_d=None):
    """The catalogue glass closest in n_d (and, if given, V_d, with 0.02 in n_d weighing like 5 in V_d)."""
    if v_d is None:
        n_d, _ = _check_nd_vd(n_d, 1.0)
    else:
        n_d, v_d = _check_nd_vd(n_d, v_d)
    best, best_distance = None, math.inf
    for glass, cat_nd, cat_vd in _catalogue().values():
        distance = ((cat_nd - n_d) / 0.02) ** 2
        if v_d is not None:
            distance += ((cat_vd - v_d) / 5.0) ** 2
        if distance < best_distance:
            best, best_distance = glass, distance
    return glass_by_name(best.name)


def clamp_warnings(glasses, clamps, messages: list) -> None:
    """Replace in ``messages`` each glass's warning by its running count of wavelength samples whose index was
    clamped at the edge of the range its formula is specified for (``clamps[i]`` for ``glasses[i]``)."""
    for glass, count in zip(glasses, clamps):
        if count:
            lo, hi = glass.valid_range_nm
            prefix = f"Glass '{glass.name}' is specified for {lo:g}-{hi:g} nm only: "
            text = prefix + f"the index was clamped at the range edge for {count} wavelength sample(s)"
            messages[:] = [m for m in messages if not m.startswith(prefix)] + [text]
