"""Measured spectra (standard illuminants, colour-checker patches, spectrum files): checked once and
resampled once onto the whole nanometres the kernels' dense table uses.

Resampling: data sampled every nanometre or more coarsely is interpolated linearly (exact at the data
points, as colour-science's tables are meant to be read); finer data (a spectrometer's 0.3 nm steps) is
averaged over each nanometre, so a narrow line keeps its energy instead of being missed between grid
points.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import PrismInputError
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

#: Wavelengths a spectrum file may hold (nm): anything outside is a unit mistake (µm, Å, cm⁻¹).
PLAUSIBLE_RANGE_NM = (100.0, 3000.0)
#: Reflectances above 1 (fluorescent whites reach ~1.05 but Prism conserves energy) are refused.
MAX_REFLECTANCE = 1.0
#: Peaks (exclusive, inclusive) that look like a reflectance written in percent.
PERCENT_PEAK = (1.5, 100.0)


def check_sampled(wavelength_nm, values, what: str, reflectance: bool = False):
    """Float64 arrays (wavelengths increasing) or ``PrismInputError`` naming ``what`` and the fix:
    too few samples, non-finite or unsorted wavelengths, wavelengths out of range or missing the visible
    range, negative values, reflectances above 1, an emitter that is black in 360-830 nm."""
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64).reshape(-1)
    values = np.asarray(values, dtype=np.float64).reshape(-1)
    if len(wavelength_nm) != len(values) or len(values) < 2:
        raise PrismInputError(f"{what} is not a spectrum: it needs at least two (wavelength in nm, value) pairs.")
    if not (np.all(np.isfinite(wavelength_nm)) and np.all(np.isfinite(values))):
        raise PrismInputError(f"{what} has NaN or infinite entries: remove or fix those rows.")
    order = np.argsort(wavelength_nm, kind="stable")
    wavelength_nm, values = wavelength_nm[order], values[order]
    if np.any(np.diff(wavelength_nm) <= 0.0):
        repeated = wavelength_nm[1:][np.diff(wavelength_nm) <= 0.0][0]
        raise PrismInputError(f"{what} lists wavelength {repeated:g} nm twice: keep one value per wavelength.")
    low, high = PLAUSIBLE_RANGE_NM
    if wavelength_nm[0] < low or wavelength_nm[-1] > high:
        raise PrismInputError(
            f"{what} has wavelengths {wavelength_nm[0]:g}-{wavelength_nm[-1]:g}, outside {low:g}-{high:g} nm: "
            "the first column must be the wavelength in nanometres (convert µm or ångström)."
        )
    inside = (wavelength_nm >= VISIBLE_MIN_NM) & (wavelength_nm <= VISIBLE_MAX_NM)
    if wavelength_nm[-1] <= VISIBLE_MIN_NM or wavelength_nm[0] >= VISIBLE_MAX_NM or not inside.any():
        raise PrismInputError(
            f"{what} covers {wavelength_nm[0]:g}-{wavelength_nm[-1]:g} nm and misses the visible range "
            f"{VISIBLE_MIN_NM:.0f}-{VISIBLE_MAX_NM:.0f} nm that Prism renders: use a spectrum measured there."
        )
    if np.any(values < 0.0):
        first = int(np.flatnonzero(values < 0.0)[0])
        raise PrismInputError(
            f"{what} is negative ({values[first]:g} at {wavelength_nm[first]:g} nm): light and reflectance "
            "cannot be negative; clip the measurement noise to 0."
        )
    if reflectance and np.any(values > MAX_REFLECTANCE):
        raise PrismInputError(_above_one(what, wavelength_nm, values))
    if not reflectance and not np.any(values[inside] > 0.0) and not _positive_between(wavelength_nm, values):
        raise PrismInputError(f"{what} emits nothing within {VISIBLE_MIN_NM:.0f}-{VISIBLE_MAX_NM:.0f} nm: "
                              "it would render black.")
    return wavelength_nm, values


def _above_one(what, wavelength_nm, values) -> str:
    """The message for a reflectance above 1. Percent is suggested only when the values look like percent
    (a peak between 1.5 and 100: a white measured in percent reaches 80-100, and a reflectance measured in
    fractions does not pass 1.5); a peak just above 1 is a reflectance that is not one."""
    peak_at = int(np.argmax(values))
    peak = float(values[peak_at])
    above = int(np.count_nonzero(values > MAX_REFLECTANCE))
    where = f"{peak:g} at {wavelength_nm[peak_at]:g} nm ({above} of {len(values)} values above 1)"
    if PERCENT_PEAK[0] < peak <= PERCENT_PEAK[1]:
        return (f"{what} reaches {where}: a reflectance lies within 0-1, and these values look like percent: "
                "divide them by 100.")
    return (f"{what} reaches {where}: a reflectance lies within 0-1 (a surface cannot reflect more light than "
            "reaches it), so this is not a reflectance: check the file's second column, or clip it to 1.")


def _positive_between(wavelength_nm, values):
    grid = np.arange(VISIBLE_MIN_NM, VISIBLE_MAX_NM + 0.5)
    return bool(np.any(np.interp(grid, wavelength_nm, values, left=0.0, right=0.0) > 0.0))


def resample_1nm(wavelength_nm, values):
    """(first_nm, values at first_nm + i nm) covering the data's whole nanometres within 360-830 nm
    (checked data, see ``check_sampled``)."""
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    values = np.asarray(values, dtype=np.float64)
    first = max(math.ceil(wavelength_nm[0]), VISIBLE_MIN_NM)
    last = min(math.floor(wavelength_nm[-1]), VISIBLE_MAX_NM)
    if last < first:  # data between two whole nanometres: keep the nanometre it is nearest
        first = last = float(np.clip(round(float(wavelength_nm.mean())), VISIBLE_MIN_NM, VISIBLE_MAX_NM))
    grid = np.arange(first, last + 0.5)
    if np.median(np.diff(wavelength_nm)) >= 1.0:
        return float(grid[0]), np.interp(grid, wavelength_nm, values)
    # Mean of the linear interpolant over each nanometre [g - 1/2, g + 1/2] (zero beyond the data).
    edges = np.concatenate([grid - 0.5, [grid[-1] + 0.5]])
    knots = np.union1d(wavelength_nm, np.clip(edges, wavelength_nm[0], wavelength_nm[-1]))
    heights = np.interp(knots, wavelength_nm, values)
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (heights[1:] + heights[:-1]) * np.diff(knots))])
    area = np.interp(edges, knots, cumulative)
    return float(grid[0]), np.diff(area)
