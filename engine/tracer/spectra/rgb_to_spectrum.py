"""RGB -> spectrum upsampling (Jakob & Hanika 2019) for linear Rec.709.

A reflectance colour becomes the smooth spectrum

    S(λ) = 1/2 + U / (2 sqrt(1 + U²)),   U = c0 λ² + c1 λ + c2   (λ in nm),

which stays within [0, 1]. Each colour's first guess is looked up in the table the kernels
upsample textured colours with (``rgb_lut``, itself made of this module's fits), then polished by a
few damped Gauss-Newton steps on our own integration (D65, CIE 1931 at 1 nm, 360-830 nm), so the
round trip RGB -> spectrum -> RGB is accurate to ~1e-5. That table is generated
(``tools/generate_rgb_lut.py``) from first guesses in the table colour-science's ``LUT3D_Jakob2019``
optimised once (``tools/generate_upsampling_table.py``, committed as ``data/rec709_jakob2019.coeff``:
``jakob_start``), so rendering does not import colour-science.

White: the gray axis is handled analytically (constant spectrum), so RGB
(1, 1, 1) is exactly 1 and (0, 0, 0) exactly 0 at every wavelength. A constant
reflectance 1 under the D65 spectrum gives Rec.709 ``white_rgb()`` ≈ (1.00016,
0.99998, 0.99976), not exactly (1, 1, 1) (the tabulated D65 spectrum and the
BT.709 white point xy = (0.3127, 0.3290) differ in the fifth digit); the polish
targets ``rgb * white_rgb()`` so colours are continuous across the gray axis.

Emission (pbrt-v4's "RGB illuminant spectrum" idea): ``RGBEmission(rgb)``
= scale · S(λ; rgb / scale) · D65(λ) / Y(D65) with scale = 2 max(rgb), so
values above 1 work and an emitter of RGB (1, 1, 1) has Y = 1 and renders
Rec.709 ≈ (1, 1, 1) through ``cie.spectral_samples_to_xyz``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import colorimetry_tables
from .cie import check_rgb, import_colour, lerp_uniform_table
from ..errors import PrismInputError
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

TABLE_PATH = Path(__file__).resolve().parent / "data" / "rec709_jakob2019.coeff"

_SPAN_NM = VISIBLE_MAX_NM - VISIBLE_MIN_NM
_POLISH_ITERATIONS = 40
_POLISH_TOLERANCE = 1e-7
_ACCEPTABLE_ERROR = 1e-5
_ROUNDING_TOLERANCE = 1e-6
_CACHE = {}


def _d65_table():
    """(wavelength_nm, relative power) of CIE D65, 300-830 nm at 5 nm (``colorimetry_tables``)."""
    tables = colorimetry_tables.load()
    return tables.d65_nm, tables.d65_power


def d65_relative_power(wavelength_nm):
    """CIE D65 relative spectral power (100 at 560 nm), linearly interpolated; 0 outside 360-830 nm."""
    table_nm, power = _d65_table()
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    inside = (wavelength_nm >= VISIBLE_MIN_NM) & (wavelength_nm <= VISIBLE_MAX_NM)
    return np.where(inside, lerp_uniform_table(wavelength_nm, table_nm[0], table_nm[1] - table_nm[0], power), 0.0)


def _integration():
    """Grid, and the kernel mapping a reflectance sampled on it to Rec.709 under D65 (Y(white) = 1)."""
    if "kernel" not in _CACHE:
        from . import cie

        wavelength_nm = np.arange(VISIBLE_MIN_NM, VISIBLE_MAX_NM + 0.5, 1.0)
        weights = np.full(wavelength_nm.shape, 1.0)
        weights[[0, -1]] = 0.5  # trapezoid, 1 nm steps
        power = d65_relative_power(wavelength_nm) * weights
        cmf = cie.cie_xyz_cmf(wavelength_nm)
        xyz_kernel = power[:, None] * cmf / np.sum(power * cmf[:, 1])
        rgb_kernel = xyz_kernel @ cie.XYZ_TO_LINEAR_REC709.T
        _CACHE["kernel"] = (wavelength_nm, rgb_kernel)
        _CACHE["white"] = rgb_kernel.sum(axis=0)
        _CACHE["d65_y"] = float(np.sum(power * cmf[:, 1]) / cie.CMF_Y_INTEGRAL)
    return _CACHE["kernel"]


def white_rgb():
    """Rec.709 colour of a constant reflectance 1 under D65 (≈ (1.00016, 0.99998, 0.99976))."""
    _integration()
    return _CACHE["white"].copy()


def jakob_start(rgb):
    """First guesses (nm coefficients [N, 3]) of reflectances ``rgb`` [N, 3] from colour-science's
    Jakob-Hanika table (imports colour-science: for ``tools/generate_rgb_lut.py``)."""
    if "jakob" not in _CACHE:
        if not TABLE_PATH.exists():
            raise RuntimeError(
                f"Missing {TABLE_PATH.name}: run tools/generate_upsampling_table.py (it ships with Prism)."
            )
        import_colour()
        from colour.recovery import LUT3D_Jakob2019

        _CACHE["jakob"] = LUT3D_Jakob2019().read(TABLE_PATH)
    return np.asarray(_CACHE["jakob"].RGB_to_coefficients(rgb), np.float64).reshape(-1, 3)


def table_start(rgb):
    """First guesses (nm coefficients [N, 3]) of reflectances ``rgb`` [N, 3] (components in [0, 1], not
    all equal) from the kernels' table (``rgb_lut``)."""
    from . import rgb_lut  # compiled code: imported when a colour is first upsampled, not with this module

    out = np.empty((len(rgb), 3))
    rgb_lut.table_coefficients(rgb_lut.load_lut(), np.ascontiguousarray(rgb, dtype=np.float64), out)
    return out


def _sigmoid(u):
    # Beyond |u| = 1e10 the sigmoid is 0 or 1 to double precision; clipping keeps u*u finite and
    # makes ±inf give exactly 0 or 1 (NaN stays NaN).
    u = np.clip(u, -1e10, 1e10)
    return 0.5 + 0.5 * (u / np.sqrt(1.0 + u * u))


def evaluate_sigmoid_polynomial(coefficients, wavelength_nm):
    """Jakob-Hanika spectrum at ``wavelength_nm``.

    ``coefficients`` [..., 3] (c0 /nm², c1 /nm, c2); ``wavelength_nm`` [..., K]
    with the same leading shape (e.g. [M, 3] with [M, K]). Returns [..., K] in
    [0, 1]; c2 = ±inf (the gray axis' black and white) gives exactly 0 or 1.
    """
    c = np.asarray(coefficients, dtype=np.float64)
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    u = (c[..., 0:1] * wavelength_nm + c[..., 1:2]) * wavelength_nm + c[..., 2:3]
    return _sigmoid(u)


def _gray_u(value):
    """U of the constant spectrum equal to ``value`` (0 -> -inf, 1 -> +inf)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (2.0 * value - 1.0) / (2.0 * np.sqrt(value * (1.0 - value)))
    return np.where(value <= 0.0, -np.inf, np.where(value >= 1.0, np.inf, u))


def _to_unit_domain(c_nm):
    """Coefficients in nm to coefficients of x = (λ - 360) / 470."""
    c0, c1, c2 = c_nm[..., 0], c_nm[..., 1], c_nm[..., 2]
    lo, span = VISIBLE_MIN_NM, _SPAN_NM
    return np.stack([c0 * span**2, (2.0 * c0 * lo + c1) * span, (c0 * lo + c1) * lo + c2], axis=-1)


def _to_nm_domain(c_unit):
    a, b, c = c_unit[..., 0], c_unit[..., 1], c_unit[..., 2]
    lo, span = VISIBLE_MIN_NM, _SPAN_NM
    return np.stack([a / span**2, b / span - 2.0 * a * lo / span**2, a * lo**2 / span**2 - b * lo / span + c], axis=-1)


def _polish(c_unit, target_rgb):
    """Levenberg-Marquardt on the Rec.709 residual, all colours at once. Returns unit-domain coefficients."""
    wavelength_nm, kernel = _integration()
    x = (wavelength_nm - VISIBLE_MIN_NM) / _SPAN_NM
    basis = np.stack([x * x, x, np.ones_like(x)], axis=-1)  # [L, 3]

    def residual(c, target):
        return _sigmoid(c @ basis.T) @ kernel - target

    r = residual(c_unit, target_rgb)
    err = np.einsum("ni,ni->n", r, r)
    damping = np.full(len(c_unit), 1e-3)
    for _ in range(_POLISH_ITERATIONS):
        active = err > _POLISH_TOLERANCE**2
        if not active.any():
            break
        u = c_unit[active] @ basis.T
        ds_du = 0.5 / (1.0 + u * u) ** 1.5
        jac = np.einsum("nl,li,lj->nij", ds_du, kernel, basis)  # d rgb_i / d c_j
        jtj = np.einsum("nki,nkj->nij", jac, jac)
        jtr = np.einsum("nki,nk->ni", jac, r[active])
        scale = np.einsum("nii->ni", jtj)
        lhs = jtj + damping[active, None, None] * (np.eye(3) * (scale[:, None, :] + 1e-12))
        step = np.linalg.solve(lhs, -jtr[..., None])[..., 0]
        trial = c_unit[active] + step
        r_trial = residual(trial, target_rgb[active])
        err_trial = np.einsum("ni,ni->n", r_trial, r_trial)
        better = err_trial < err[active]
        idx = np.flatnonzero(active)
        accept = idx[better]
        c_unit[accept] = trial[better]
        r[accept] = r_trial[better]
        err[accept] = err_trial[better]
        damping[accept] = np.maximum(damping[accept] / 3.0, 1e-9)
        damping[idx[~better]] *= 4.0
    return c_unit


def _residual_norm(c_unit, target_rgb):
    wavelength_nm, kernel = _integration()
    x = (wavelength_nm - VISIBLE_MIN_NM) / _SPAN_NM
    r = _sigmoid(c_unit[:, :1] * x * x + c_unit[:, 1:2] * x + c_unit[:, 2:3]) @ kernel - target_rgb
    return np.abs(r).max(axis=-1)


def _fit(start_unit, target_rgb):
    """Polish from the table's guess; colours it leaves unconverged restart from generic shapes."""
    best = _polish(start_unit.copy(), target_rgb)
    best_err = _residual_norm(best, target_rgb)
    luminance = np.clip(target_rgb @ np.array([0.2126, 0.7152, 0.0722]), 0.02, 0.98)
    for a in (0.0, -8.0, 8.0, -30.0):
        failed = np.flatnonzero(best_err > _ACCEPTABLE_ERROR)
        if failed.size == 0:
            break
        start = np.stack([np.full(failed.size, a), np.full(failed.size, -a), _gray_u(luminance[failed])], -1)
        trial = _polish(start, target_rgb[failed])
        trial_err = _residual_norm(trial, target_rgb[failed])
        better = trial_err < best_err[failed]
        best[failed[better]] = trial[better]
        best_err[failed[better]] = trial_err[better]
    return best


def reflectance_coefficients(rgb, start=table_start):
    """Jakob-Hanika coefficients [..., 3] (nm units) of linear Rec.709 reflectances ``rgb`` [..., 3].

    ``start`` gives the fit's first guesses (``table_start``, or ``jakob_start`` to make that table).

    Components must be finite and within [0, 1] (a reflectance above 1 would
    create energy; 1 + 1e-6 is taken as 1): anything else raises ``PrismInputError``. Gray colours
    (r = g = b) give c0 = c1 = 0 and a constant spectrum, exactly 0 and 1 at
    the ends.
    """
    rgb = check_rgb(rgb, "Reflectance colour")
    rgb = np.where((rgb > 1.0) & (rgb <= 1.0 + _ROUNDING_TOLERANCE), 1.0, rgb)  # float32 round-off
    if np.any(rgb > 1.0):
        raise PrismInputError(
            f"Reflectance colour {rgb.tolist()} has a component above 1: a surface cannot reflect more "
            "light than it receives; use values in 0-1 (or make the material emissive)."
        )
    shape = rgb.shape
    flat = rgb.reshape(-1, 3)
    out = np.zeros(flat.shape)
    gray = (flat[:, 0] == flat[:, 1]) & (flat[:, 1] == flat[:, 2])
    out[gray, 2] = _gray_u(flat[gray, 0])
    coloured = np.flatnonzero(~gray)
    if coloured.size:
        target = flat[coloured] * white_rgb()
        out[coloured] = _to_nm_domain(_fit(_to_unit_domain(start(flat[coloured])), target))
    return out.reshape(shape)


class RGBEmission:
    """Emission spectrum of a linear Rec.709 colour ``rgb`` (components >= 0, any magnitude).

    ``evaluate(wavelength_nm)`` = scale · S(λ) · D65(λ) / Y(D65), scale =
    2 max(rgb), S the reflectance spectrum of rgb / scale (largest component
    1/2). Its XYZ through ``cie`` is that of ``rgb`` (times the D65 white
    mismatch ``white_rgb()``), so RGB (1, 1, 1) has luminance Y = 1.
    """

    def __init__(self, rgb):
        rgb = check_rgb(rgb, "Emission colour")
        if rgb.shape != (3,):
            raise PrismInputError(f"Emission colour must be one (R, G, B) triple, got shape {rgb.shape}.")
        self.rgb = rgb
        self.scale = 2.0 * float(rgb.max())
        base = rgb / self.scale if self.scale > 0.0 else np.zeros(3)
        self.coefficients = reflectance_coefficients(base)
        _integration()
        self._d65_norm = _CACHE["d65_y"]

    def evaluate(self, wavelength_nm):
        """Relative spectral radiance at ``wavelength_nm`` (any shape); 0 outside 360-830 nm."""
        if self.scale == 0.0:
            return np.zeros(np.shape(wavelength_nm))
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        s = evaluate_sigmoid_polynomial(self.coefficients, wavelength_nm.reshape(-1)).reshape(wavelength_nm.shape)
        return self.scale * s * d65_relative_power(wavelength_nm) / self._d65_norm
