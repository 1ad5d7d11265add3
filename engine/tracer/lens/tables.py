"""A lens system as flat float64 arrays, the form the compiled lens kernels read.

``LensTables`` fields (S surfaces, scene side first; lens coordinates in mm as ``system.py``
defines them):

- ``vertex_z_mm`` [S]: axial position of each surface vertex (front vertex at 0);
- ``curvature_per_mm`` [S]: 1 / radius (0 for a flat surface and for the stop);
- ``semi_aperture_mm`` [S]: clear aperture radius (the stop's opening radius for the stop);
- ``is_stop`` [S] bool: the aperture stop (blocks outside its opening, never refracts);
- ``medium_rows`` [S + 1, GLASS_ROW]: the glass rows of ``spectra.dispersion`` of the media
  between the surfaces: row ``i`` is the medium on the scene side of surface ``i`` and row
  ``i + 1`` the one on its film side (rows 0 and S are air).

A module-level namedtuple of arrays, so numba caches the kernels that take it.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from ..spectra.dispersion import glass_row
from ..spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

LensTables = namedtuple("LensTables", "vertex_z_mm curvature_per_mm semi_aperture_mm is_stop medium_rows")

# Wavelengths at which a medium given only as a function is probed to recognise its law.
_PROBE_WAVELENGTHS_NM = np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, 9)
_LAW_TOLERANCE = 1e-12


def lens_tables(system) -> LensTables:
    """The kernel tables of a ``LensSystem`` (see the module docstring)."""
    surfaces = system.surfaces
    media = [None] + [s.medium for s in surfaces]
    return LensTables(
        vertex_z_mm=np.ascontiguousarray(system.vertex_z_mm, dtype=np.float64),
        curvature_per_mm=np.array([s.curvature_per_mm for s in surfaces], dtype=np.float64),
        semi_aperture_mm=np.array([s.semi_aperture_mm for s in surfaces], dtype=np.float64),
        is_stop=np.array([s.is_stop for s in surfaces], dtype=np.bool_),
        medium_rows=np.array([medium_row(m) for m in media], dtype=np.float64),
    )


def medium_row(medium) -> np.ndarray:
    """The glass row of a lens medium: air (or ``None``), a ``GlassMedium`` (its catalogue or
    Abbe glass), or a medium known only as a function of wavelength whose values follow a
    constant or Cauchy law n = A + B / λ² exactly (``media.constant_medium`` and the Cauchy
    media of tests). Any other function has no kernel form: ``TypeError``."""
    from ..spectra.glass import CauchyGlass, ConstantGlass

    if medium is None or getattr(medium, "is_air", False):
        return glass_row(None)
    glass = getattr(medium, "glass", None)
    if glass is not None:
        return glass_row(glass)
    wavelength_nm = _PROBE_WAVELENGTHS_NM
    n = np.asarray(medium.index(wavelength_nm), dtype=np.float64)
    design = np.column_stack([np.ones_like(wavelength_nm), 1.0 / wavelength_nm**2])
    (a, b_nm2), *_ = np.linalg.lstsq(design, n, rcond=None)
    if np.max(np.abs(design @ (a, b_nm2) - n)) > _LAW_TOLERANCE * np.max(np.abs(n)):
        label = getattr(medium, "label", repr(medium))
        raise TypeError(
            f"Lens medium '{label}' has no kernel form: its index is neither constant nor A + B/λ². "
            "Give the surface a catalogue glass or n_d and V_d (a GlassMedium)."
        )
    if np.ptp(n) <= _LAW_TOLERANCE * np.max(np.abs(n)):
        return glass_row(ConstantGlass(float(n[0])))
    row = glass_row(CauchyGlass(getattr(medium, "label", "cauchy"), a, b_nm2))
    row[1:3] = (0.0, np.inf)  # a function has no valid range: never clamp it
    return row
