"""Focusing: the film distance that images a given object sharpest, and axial colour.

The paraxial (thick-lens) solution comes first; it is then refined by minimising the RMS
spot radius of an on-axis point traced through the real surfaces (which moves focus by
the spherical aberration). Distances: ``sensor_distance_mm`` is from the last surface
vertex to the film; ``focus_distance_mm`` is from the FILM to the object (as on a focus
scale and as Blender's focus distance, since the film is at the camera origin).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import PrismInputError
from .media import C_LINE_NM, D_LINE_NM, F_LINE_NM
from .paraxial import paraxial_data, sensor_distance_for_focus
from .system import TOWARD_FILM

PUPIL_OVERFILL = 1.25  # sample beyond the paraxial pupil: the stop clips the real bundle
PUPIL_GRID = 64


@dataclass(frozen=True)
class FocusResult:
    """Where to put the film: ``sensor_distance_mm`` (refined), the paraxial value, the
    object position used (lens coordinates, -inf for infinity) and the RMS spot radius."""

    sensor_distance_mm: float
    paraxial_sensor_distance_mm: float
    object_z_mm: float
    rms_spot_mm: float
    wavelength_nm: float


def axial_bundle(system, object_z_mm, wavelength_nm=D_LINE_NM, grid=PUPIL_GRID):
    """Rays from an on-axis object point (``-inf`` = at infinity) that get through the lens.

    The entrance pupil is filled with a square grid of ``grid`` x ``grid`` points over
    ``PUPIL_OVERFILL`` times its paraxial diameter. Returns (origins, directions) [M, 3]
    after the last surface, lens coordinates.
    """
    pupil = paraxial_data(system, wavelength_nm)
    half = 0.5 * pupil.entrance_pupil_diameter_mm * PUPIL_OVERFILL
    u = (np.arange(grid) + 0.5) / grid * 2.0 - 1.0
    x, y = np.meshgrid(u * half, u * half)
    inside = x**2 + y**2 <= half**2
    x, y = x[inside], y[inside]
    if np.isfinite(object_z_mm):
        target = np.column_stack([x, y, np.full_like(x, pupil.entrance_pupil_z_mm)])
        origins = np.zeros_like(target)
        origins[:, 2] = object_z_mm
        directions = target - origins
    else:
        start = -10.0 - max(s.aperture_mm for s in system.surfaces)
        origins = np.column_stack([x, y, np.full_like(x, start)])
        directions = np.tile([0.0, 0.0, 1.0], (len(x), 1))
    result = system.trace(origins, directions, wavelength_nm, toward=TOWARD_FILM)
    return result.origins[result.alive], result.directions[result.alive]


def rms_spot_radius_mm(origins, directions, film_z_mm) -> float:
    """RMS distance from the centroid of where the rays cross the plane z = ``film_z_mm``."""
    t = (film_z_mm - origins[:, 2]) / directions[:, 2]
    xy = origins[:, :2] + t[:, None] * directions[:, :2]
    xy -= xy.mean(axis=0)
    return float(np.sqrt(np.mean(np.einsum("ij,ij->i", xy, xy))))


def object_z_for_focus(system, focus_distance_mm, wavelength_nm=D_LINE_NM) -> float:
    """Lens-coordinate z of an axial object ``focus_distance_mm`` in front of the paraxially focused film."""
    if not np.isfinite(focus_distance_mm):
        return -np.inf
    s = sensor_distance_for_focus(system, focus_distance_mm, wavelength_nm)
    return system.rear_z_mm + s - float(focus_distance_mm)


def best_focus(system, object_z_mm, wavelength_nm=D_LINE_NM, paraxial_guess_mm=None) -> FocusResult:
    """Film distance minimising the RMS spot of an axial point at ``object_z_mm`` (fixed).

    Bounded scalar minimisation (scipy) around the paraxial image distance.
    """
    from scipy.optimize import minimize_scalar

    from .paraxial import image_distance_mm

    guess = paraxial_guess_mm if paraxial_guess_mm is not None else image_distance_mm(
        system, object_z_mm, wavelength_nm
    )
    origins, directions = axial_bundle(system, object_z_mm, wavelength_nm)
    if len(origins) < 8:
        return FocusResult(guess, guess, object_z_mm, float("nan"), float(wavelength_nm))
    rear = system.rear_z_mm
    efl = abs(paraxial_data(system, wavelength_nm).efl_mm)
    width = max(0.2 * efl, 1.0)
    lo, hi = max(guess - width, 1e-3), guess + width
    if not hi > lo:
        raise PrismInputError(
            f"Lens '{system.name}' images {wavelength_nm:g} nm light {-guess:.4g} mm inside its last surface, "
            "where no film can go: check its thicknesses and radii."
        )
    res = minimize_scalar(
        lambda s: rms_spot_radius_mm(origins, directions, rear + s),
        bounds=(lo, hi), method="bounded", options={"xatol": 1e-7},
    )
    return FocusResult(float(res.x), float(guess), float(object_z_mm), float(res.fun), float(wavelength_nm))


def focus(system, focus_distance_mm=np.inf, wavelength_nm=D_LINE_NM, refine=True) -> FocusResult:
    """Film distance that focuses an object ``focus_distance_mm`` from the film (``inf`` allowed)."""
    paraxial = sensor_distance_for_focus(system, focus_distance_mm, wavelength_nm)
    object_z = object_z_for_focus(system, focus_distance_mm, wavelength_nm)
    if not refine:
        return FocusResult(paraxial, paraxial, object_z, float("nan"), float(wavelength_nm))
    return best_focus(system, object_z, wavelength_nm, paraxial)


def focus_shift_mm(system, focus_distance_mm=np.inf, blue_nm=F_LINE_NM, red_nm=C_LINE_NM, refine=False) -> float:
    """Longitudinal chromatic aberration: film distance at ``red_nm`` minus at ``blue_nm``.

    Positive when red focuses farther from the lens (an uncorrected positive lens).
    The object is fixed where the d-line focus puts it.
    """
    object_z = object_z_for_focus(system, focus_distance_mm)
    if refine:
        return best_focus(system, object_z, red_nm).sensor_distance_mm - best_focus(
            system, object_z, blue_nm
        ).sensor_distance_mm
    from .paraxial import image_distance_mm

    return image_distance_mm(system, object_z, red_nm) - image_distance_mm(system, object_z, blue_nm)
