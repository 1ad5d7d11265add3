"""Checks that a loaded lens prescription describes a lens that can be built.

Every failure raises ``LensFileError`` naming the file, the line and the problem.
"""

from __future__ import annotations

import numpy as np

from ..errors import LensFileError

#: Real photographic lenses have up to about 50 surfaces; every surface costs every traced ray.
MAX_SURFACES = 100
#: 100 m: any length beyond this is a typo or a unit error (lens files are in millimetres).
MAX_LENGTH_MM = 1.0e5
#: Radii beyond this are flat for any aperture Prism allows: write ``inf`` (``0`` marks the stop in .dat).
MAX_RADIUS_MM = 1.0e9


def where(path, line) -> str:
    """``"lens.dat, line 7"`` style prefix for messages."""
    return f"{path}, line {line}" if line else f"{path}"


def validate_surfaces(surfaces, path) -> None:
    """Raise ``LensFileError`` for a prescription no lens can have.

    Checks: at least two surfaces, positive clear apertures, non-negative thicknesses,
    exactly one aperture stop, each clear aperture within its sphere, and adjacent
    surfaces that do not cut through each other inside their common clear aperture.
    """
    if len(surfaces) < 2:
        raise LensFileError(f"{path}: a lens needs at least two surfaces (found {len(surfaces)}).")
    if len(surfaces) > MAX_SURFACES:
        raise LensFileError(
            f"{path}: {len(surfaces)} surfaces; Prism traces lenses of up to {MAX_SURFACES} (real lenses have "
            "about 50 at most), as each surface slows every ray."
        )
    for s in surfaces:
        _check_size(s, path)
    stops = [s for s in surfaces if s.is_stop]
    if not stops:
        raise LensFileError(
            f"{path}: no aperture stop. Mark one surface as the stop (radius 0 in a .dat file, "
            "'stop = true' in a .lens file)."
        )
    if len(stops) > 1:
        lines = ", ".join(str(s.line) for s in stops)
        raise LensFileError(f"{path}: more than one aperture stop (lines {lines}); keep exactly one.")
    for i, s in enumerate(surfaces):
        at = where(path, s.line)
        if not s.aperture_mm > 0:
            kind = "negative" if s.aperture_mm < 0 else "zero"
            raise LensFileError(
                f"{at}: {kind} clear aperture {s.aperture_mm:g} mm; the aperture is a diameter and must be positive."
            )
        if s.thickness_mm < 0 and i < len(surfaces) - 1:
            raise LensFileError(f"{at}: negative thickness {s.thickness_mm:g} mm to the next surface.")
        if not s.is_stop and np.isfinite(s.radius_mm) and s.semi_aperture_mm > abs(s.radius_mm):
            raise LensFileError(
                f"{at}: clear aperture {s.aperture_mm:g} mm is wider than the sphere of radius "
                f"{s.radius_mm:g} mm can be; reduce the aperture or the curvature."
            )
        n_d = float(s.medium.n_d)
        if not n_d >= 1.0:
            raise LensFileError(f"{at}: refractive index {n_d:g} is below 1.")
    _check_no_overlap(surfaces, path)


def _check_size(surface, path) -> None:
    at = where(path, surface.line)
    for name, value in (("thickness", surface.thickness_mm), ("clear aperture", surface.aperture_mm)):
        if abs(value) > MAX_LENGTH_MM:
            raise LensFileError(
                f"{at}: {name} {value:g} mm is more than {MAX_LENGTH_MM:g} mm (100 m): lens files are in millimetres."
            )
    if np.isfinite(surface.radius_mm) and abs(surface.radius_mm) > MAX_RADIUS_MM:
        raise LensFileError(f"{at}: radius {surface.radius_mm:g} mm is flat for any aperture: write inf instead.")


def _check_no_overlap(surfaces, path) -> None:
    z = np.concatenate([[0.0], np.cumsum([s.thickness_mm for s in surfaces[:-1]])])
    for i in range(len(surfaces) - 1):
        a, b = surfaces[i], surfaces[i + 1]
        r = np.linspace(0.0, min(a.semi_aperture_mm, b.semi_aperture_mm), 257)
        gap = (z[i + 1] + b.sag_mm(r)) - (z[i] + a.sag_mm(r))
        if np.min(gap) < -1e-9:
            k = int(np.argmin(gap))
            raise LensFileError(
                f"{where(path, b.line)}: this surface cuts through the previous one (line {a.line}): at "
                f"{r[k]:.3g} mm from the axis it lies {-gap[k]:.3g} mm in front of it. Increase the "
                "thickness between them or reduce their clear apertures."
            )
