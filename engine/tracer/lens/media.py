"""The optical media between lens surfaces: air, or a glass with an index per wavelength.

A medium is any object with ``index(wavelength_nm) -> ndarray`` (float64, same shape),
``n_d`` (index at the helium d line, 587.56 nm) and ``label`` (for messages and the
overlay). Glasses come from ``engine.tracer.spectra.glass``; this module only adapts them, so
the lens code never keeps a second glass catalogue.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

D_LINE_NM = 587.5618
F_LINE_NM = 486.1327
C_LINE_NM = 656.2725


class Air:
    """Air treated as vacuum (index 1 at every wavelength), as lens prescriptions assume."""

    label = "air"
    n_d = 1.0
    v_d = float("inf")
    is_air = True

    def index(self, wavelength_nm):
        return np.ones_like(np.asarray(wavelength_nm, dtype=np.float64))

    def __repr__(self):
        return "Air()"


AIR = Air()


@dataclass(frozen=True)
class GlassMedium:
    """A glass: ``glass`` is any object with ``index(wavelength_nm)`` (a catalogue Glass).

    ``label`` says where it came from, e.g. ``"N-BK7"`` or ``"n_d 1.67, V_d 47.11 (as N-BAF10)"``.
    """

    glass: object
    label: str
    is_air = False

    def index(self, wavelength_nm):
        return np.asarray(self.glass.index(np.asarray(wavelength_nm, dtype=np.float64)), dtype=np.float64)

    @property
    def n_d(self) -> float:
        return float(self.index(np.array([D_LINE_NM]))[0])

    @property
    def v_d(self) -> float:
        n = self.index(np.array([D_LINE_NM, F_LINE_NM, C_LINE_NM]))
        return float((n[0] - 1.0) / (n[1] - n[2]))


@dataclass(frozen=True)
class FunctionMedium:
    """A medium from a plain callable ``index_fn(wavelength_nm) -> index`` (tests, tools)."""

    index_fn: Callable
    label: str = "custom"
    is_air = False

    def index(self, wavelength_nm):
        wl = np.asarray(wavelength_nm, dtype=np.float64)
        return np.broadcast_to(np.asarray(self.index_fn(wl), dtype=np.float64), wl.shape).copy()

    @property
    def n_d(self) -> float:
        return float(self.index(np.array([D_LINE_NM]))[0])


def constant_medium(n: float, label: str | None = None) -> FunctionMedium:
    """A dispersion-free medium of index ``n`` (tests)."""
    return FunctionMedium(lambda wl: np.full_like(wl, float(n)), label or f"n {n:g}")


def catalogue_medium(name: str) -> GlassMedium:
    """The catalogue glass ``name``; raises ``UnknownGlassError`` if it does not exist."""
    from ..spectra.glass import glass_by_name

    return GlassMedium(glass_by_name(name), name)


def abbe_medium(n_d: float, v_d: float, label: str | None = None) -> GlassMedium:
    """A glass given by its catalogue-style n_d and V_d."""
    from ..spectra.glass import glass_from_abbe

    return GlassMedium(glass_from_abbe(float(n_d), float(v_d)), label or f"n_d {n_d:g}, V_d {v_d:g}")


def assumed_medium(n_d: float) -> tuple[GlassMedium, str]:
    """A glass for a bare index (legacy files): n_d kept, V_d of the nearest catalogue glass.

    Returns the medium and the name of the catalogue glass whose V_d was assumed.
    """
    from ..spectra.glass import glass_from_abbe, nearest_catalogue_glass

    nearest = nearest_catalogue_glass(float(n_d))
    name = getattr(nearest, "name", None) or str(nearest)
    v_d = float(nearest.v_d)
    glass = glass_from_abbe(float(n_d), v_d)
    return GlassMedium(glass, f"n_d {n_d:g}, V_d {v_d:.2f} (as {name})"), name
