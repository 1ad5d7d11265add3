"""CIE 1931 colorimetry: colour-matching functions, XYZ estimators, Rec.709.

Tables come from colour-science through the file Prism ships (``colorimetry_tables``: a
render does not import colour-science, which takes half a second) and are loaded lazily, so importing
this module is cheap. ``CMF_Y_INTEGRAL`` and ``XYZ_TO_LINEAR_REC709`` are module attributes computed
on first access.

Conventions: wavelengths in nm; the CMFs are the CIE 1931 2° observer tabulated
at 1 nm over 360-830 nm and linearly interpolated (zero outside). ``Y`` is
normalised by ``CMF_Y_INTEGRAL`` = ∫ ȳ dλ (trapezoid over the table, which is the
exact integral of the interpolant), so a spectrum equal to 1 at every wavelength
has Y = 1, and an emitter or white surface of luminance 1 maps to Rec.709
(1, 1, 1) when its chromaticity is D65.
"""

from __future__ import annotations

import numpy as np

from ..errors import PrismInputError
from . import colorimetry_tables
from .trapezoid import trapezoid

_LAZY = {}


def import_colour():
    """Import colour-science (half a second), silencing its note that matplotlib is absent: for measured
    spectra, illuminants by name and file formats, which a render imports only when a scene uses them."""
    import warnings

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Matplotlib.*")
        import colour
    return colour


def _cmf_table():
    """(wavelength_nm [M], xyz [M, 3]) of the observer (``colorimetry_tables``, read once per process)."""
    tables = colorimetry_tables.load()
    return tables.cmf_nm, tables.cmf_xyz


def _cmf_y_integral():
    wavelength_nm, xyz = _cmf_table()
    return float(trapezoid(xyz[:, 1], wavelength_nm))


def _xyz_to_linear_rec709():
    return colorimetry_tables.load().xyz_to_rec709


_LAZY_FACTORIES = {"CMF_Y_INTEGRAL": _cmf_y_integral, "XYZ_TO_LINEAR_REC709": _xyz_to_linear_rec709}


def __getattr__(name):
    if name in _LAZY_FACTORIES:
        if name not in _LAZY:
            _LAZY[name] = _LAZY_FACTORIES[name]()
        return _LAZY[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def lerp_uniform_table(x, x0, dx, table):
    """Linear interpolation in a table sampled at ``x0 + i * dx`` ([M] or [M, C]); zero outside, NaN stays NaN.

    Direct index arithmetic instead of a binary search (``np.interp``): the
    hot path evaluates it for every wavelength of every path.
    """
    x = np.asarray(x, dtype=np.float64)
    table = np.asarray(table, dtype=np.float64)
    columns = table.reshape(len(table), -1).T  # [C, M]
    slopes = np.diff(columns, axis=1)
    position = ((x - x0) / dx).reshape(-1)
    outside = ~((position >= 0.0) & (position <= len(table) - 1))  # NaN counts as outside
    position[outside] = 0.0
    index = np.minimum(position.astype(np.intp), len(table) - 2)
    frac = position - index
    out = np.empty((len(columns), position.size))
    for c in range(len(columns)):  # one pass per table column (3 for the CMFs), not per sample
        np.multiply(slopes[c].take(index), frac, out=out[c])
        out[c] += columns[c].take(index)
    out[:, outside] = 0.0
    out[:, np.isnan(x).reshape(-1)] = np.nan
    out = out.T if table.ndim == 2 else out[0]
    return out.reshape(x.shape + table.shape[1:])


def cie_xyz_cmf(wavelength_nm):
    """CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at ``wavelength_nm``; shape [..., 3].

    Linear interpolation of the 1 nm table; zero outside 360-830 nm; NaN in, NaN out.
    """
    table_nm, xyz = _cmf_table()
    return lerp_uniform_table(wavelength_nm, table_nm[0], table_nm[1] - table_nm[0], xyz)


def xyz_to_linear_rec709(xyz):
    """CIE XYZ [..., 3] to scene-linear Rec.709 [..., 3] (D65 white, no clipping)."""
    return np.asarray(xyz, dtype=np.float64) @ __getattr__("XYZ_TO_LINEAR_REC709").T


def linear_rec709_to_xyz(rgb):
    """Scene-linear Rec.709 [..., 3] to CIE XYZ [..., 3]."""
    return np.asarray(rgb, dtype=np.float64) @ np.linalg.inv(__getattr__("XYZ_TO_LINEAR_REC709")).T


def spectral_samples_to_xyz(radiance, wavelength_nm, pdf):
    """Monte Carlo estimate of XYZ from K wavelength samples per path.

    ``radiance``, ``wavelength_nm``, ``pdf``: [N, K] (spectral radiance at each
    sampled wavelength, and the density each wavelength was drawn with).
    Returns [N, 3] = mean over K of ``L * cmf / pdf`` divided by ∫ȳ, so an
    equal-energy spectrum of 1 has expected Y = 1. Samples with pdf <= 0
    contribute nothing.
    """
    radiance = np.asarray(radiance, dtype=np.float64)
    pdf = np.asarray(pdf, dtype=np.float64)
    if radiance.ndim == 1:
        radiance, pdf, wavelength_nm = radiance[None], pdf[None], np.asarray(wavelength_nm)[None]
    safe_pdf = np.where(pdf > 0.0, pdf, 1.0)
    weight = np.where(pdf > 0.0, radiance / safe_pdf, 0.0)
    cmf = cie_xyz_cmf(wavelength_nm)
    xyz = np.einsum("nk,nkc->nc", weight, cmf) / weight.shape[-1]
    return xyz / __getattr__("CMF_Y_INTEGRAL")


def monochromatic_rgb(wavelength_nm):
    """Display colour of monochromatic light, for overlays: linear Rec.709 [..., 3].

    The XYZ of a line at ``wavelength_nm`` is converted to Rec.709, negative
    channels (the line lies outside the Rec.709 gamut) are clipped to 0, and the
    result is scaled so its largest channel is 1. Brightness is therefore not
    represented; wavelengths outside 360-830 nm give black.
    """
    rgb = np.clip(xyz_to_linear_rec709(cie_xyz_cmf(wavelength_nm)), 0.0, None)
    peak = rgb.max(axis=-1, keepdims=True)
    return np.where(peak > 0.0, rgb / np.where(peak > 0.0, peak, 1.0), 0.0)


def spectrum_luminance(spectrum_fn):
    """Y of a spectrum given as a callable of wavelength (nm), by trapezoid on the 1 nm CMF grid.

    ``spectrum_fn(wavelength_nm [M]) -> [..., M]``; returns [...]. Used to
    normalise emission spectra to a luminance; only for spectra smooth on a
    1 nm scale (not narrow lines).
    """
    table_nm, xyz = _cmf_table()
    values = np.asarray(spectrum_fn(table_nm), dtype=np.float64)
    return trapezoid(values * xyz[:, 1], table_nm, axis=-1) / __getattr__("CMF_Y_INTEGRAL")


def spectrum_to_xyz(spectrum_fn):
    """XYZ [..., 3] of a spectrum given as a callable of wavelength (nm) (trapezoid on the 1 nm grid; smooth spectra)."""
    table_nm, xyz = _cmf_table()
    values = np.asarray(spectrum_fn(table_nm), dtype=np.float64)
    return trapezoid(values[..., None] * xyz, table_nm, axis=-2) / __getattr__("CMF_Y_INTEGRAL")


def check_rgb(rgb, what):
    """Validate a colour triple (finite, non-negative); returns float64 [..., 3]."""
    rgb = np.asarray(rgb, dtype=np.float64)
    if rgb.shape[-1:] != (3,):
        raise PrismInputError(f"{what}: a colour needs three components (R, G, B), got shape {rgb.shape}.")
    if not np.all(np.isfinite(rgb)):
        raise PrismInputError(f"{what}: colour {rgb.tolist()} contains NaN or infinity; set a finite colour.")
    if np.any(rgb < 0.0):
        raise PrismInputError(f"{what}: colour {rgb.tolist()} has a negative component; use values >= 0.")
    return rgb
