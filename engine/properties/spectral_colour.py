"""Quick spectrum → display colour for UI swatches and plots (numpy only, no colour-science).

The colour-matching functions are the multi-lobe Gaussian fit of the CIE 1931 2°
observer by Wyman, Sloan and Shirley, "Simple Analytic Approximations to the CIE
XYZ Color Matching Functions", JCGT 2(2), 2013 (accurate to ~1 % of the peak) —
good enough for a swatch, light enough to evaluate while Blender draws a panel.
Renders use the tabulated CMFs of ``engine.tracer``.
"""

from __future__ import annotations

import numpy as np

from ..tracer.spectra.wavelengths import VISIBLE_NM_GRID as WAVELENGTHS_NM

# (weight, mean_nm, sigma_below_nm, sigma_above_nm) per lobe, from Wyman et al. 2013, section 2.
_LOBES = {
    "x": ((1.056, 599.8, 37.9, 31.0), (0.362, 442.0, 16.0, 26.7), (-0.065, 501.1, 20.4, 26.2)),
    "y": ((0.821, 568.8, 46.9, 40.5), (0.286, 530.9, 16.3, 31.1)),
    "z": ((1.217, 437.0, 11.8, 36.0), (0.681, 459.0, 26.0, 13.8)),
}

# CIE XYZ → linear Rec.709 (D65), as in IEC 61966-2-1.
XYZ_TO_REC709 = np.array(
    [
        [3.2404542, -1.5371385, -0.4985314],
        [-0.9692660, 1.8760108, 0.0415560],
        [0.0556434, -0.2040259, 1.0572252],
    ]
)

_PLANCK_H = 6.62607015e-34  # J s
_LIGHT_C = 2.99792458e8  # m / s
_BOLTZMANN_K = 1.380649e-23  # J / K


def cmf_xyz(wavelength_nm) -> np.ndarray:
    """Approximate CIE 1931 x̄, ȳ, z̄ at ``wavelength_nm`` → array [..., 3]."""
    lam = np.asarray(wavelength_nm, dtype=np.float64)
    out = []
    for lobes in _LOBES.values():
        total = np.zeros_like(lam)
        for weight, mean, sigma_low, sigma_high in lobes:
            sigma = np.where(lam < mean, sigma_low, sigma_high)
            total += weight * np.exp(-0.5 * ((lam - mean) / sigma) ** 2)
        out.append(total)
    return np.stack(out, axis=-1)


def planck_radiance(wavelength_nm, temperature_k: float) -> np.ndarray:
    """Blackbody spectral radiance (W sr^-1 m^-3) at ``wavelength_nm`` for ``temperature_k``."""
    lam_m = np.asarray(wavelength_nm, dtype=np.float64) * 1e-9
    exponent = _PLANCK_H * _LIGHT_C / (lam_m * _BOLTZMANN_K * float(temperature_k))
    return 2.0 * _PLANCK_H * _LIGHT_C**2 / lam_m**5 / np.expm1(np.minimum(exponent, 700.0))


def spectrum_to_display_rgb(spectrum) -> tuple[float, float, float]:
    """Linear Rec.709 colour of a spectrum sampled on ``WAVELENGTHS_NM``, scaled so the largest
    channel is 1; out-of-gamut (negative) channels are clipped to 0."""
    xyz = np.asarray(spectrum, dtype=np.float64) @ cmf_xyz(WAVELENGTHS_NM)
    rgb = np.clip(XYZ_TO_REC709 @ xyz, 0.0, None)
    peak = rgb.max()
    if not np.isfinite(peak) or peak <= 0.0:
        return (0.0, 0.0, 0.0)
    return tuple(float(c) for c in rgb / peak)


def blackbody_display_rgb(temperature_k: float) -> tuple[float, float, float]:
    """Swatch colour of a blackbody at ``temperature_k`` (largest channel 1)."""
    return spectrum_to_display_rgb(planck_radiance(WAVELENGTHS_NM, max(float(temperature_k), 1.0)))


def line_display_rgb(wavelength_nm: float, width_nm: float) -> tuple[float, float, float]:
    """Swatch colour of a Gaussian emission line at ``wavelength_nm`` with full width at half
    maximum ``width_nm`` (largest channel 1)."""
    sigma = max(float(width_nm), 0.5) / 2.3548200450309493
    return spectrum_to_display_rgb(np.exp(-0.5 * ((WAVELENGTHS_NM - wavelength_nm) / sigma) ** 2))
