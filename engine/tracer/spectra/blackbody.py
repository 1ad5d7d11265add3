"""Planck's law and the luminance-normalised blackbody spectrum.

Constants are CODATA 2018 exact SI values. Radiance is computed in float64 with
``expm1`` and the exponent capped, so very short wavelengths at low temperature
give 0 instead of overflowing.
"""

from __future__ import annotations

import numpy as np

from ..errors import PrismInputError

MIN_TEMPERATURE_K = 1000.0
MAX_TEMPERATURE_K = 40000.0

PLANCK_H_J_S = 6.62607015e-34
SPEED_OF_LIGHT_M_S = 299792458.0
BOLTZMANN_J_K = 1.380649e-23

_C1 = 2.0 * PLANCK_H_J_S * SPEED_OF_LIGHT_M_S**2  # W m^2 / sr
_C2 = PLANCK_H_J_S * SPEED_OF_LIGHT_M_S / BOLTZMANN_J_K  # m K
_MAX_EXPONENT = 700.0  # exp(700) ~ 1e304: beyond it the radiance is 0 in float64 anyway


def check_temperature(temperature_k, what="Blackbody"):
    """Raise ``PrismInputError`` unless every temperature is finite and within 1000-40000 K."""
    t = np.asarray(temperature_k, dtype=np.float64)
    bad = ~((t >= MIN_TEMPERATURE_K) & (t <= MAX_TEMPERATURE_K))
    if np.any(bad):
        value = t.reshape(-1)[np.flatnonzero(bad.reshape(-1))[0]]
        raise PrismInputError(
            f"{what} temperature {value:g} K is outside {MIN_TEMPERATURE_K:.0f}–{MAX_TEMPERATURE_K:.0f} K: "
            "set a colour temperature in that range."
        )
    return t


def planck_spectral_radiance(wavelength_nm, temperature_k):
    """Blackbody spectral radiance in W·sr⁻¹·m⁻²·nm⁻¹ (broadcasts wavelength and temperature).

    ``B(λ, T) = 2 h c² / λ⁵ / (exp(h c / (λ k T)) - 1)``, per nanometre of
    wavelength. Temperatures outside 1000-40000 K (or NaN) raise
    ``PrismInputError``; non-positive wavelengths raise too.
    """
    t = check_temperature(temperature_k)
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    if not np.all(wavelength_nm > 0.0):
        raise PrismInputError("Planck radiance needs positive, finite wavelengths in nm.")
    wavelength_m = wavelength_nm * 1e-9
    exponent = _C2 / (wavelength_m * t)
    capped = np.minimum(exponent, _MAX_EXPONENT)
    radiance_per_m = _C1 / (wavelength_m**5 * np.expm1(capped))
    return np.where(exponent > _MAX_EXPONENT, 0.0, radiance_per_m * 1e-9)


def blackbody_luminance(temperature_k):
    """Y (cie.py normalisation) of ``planck_spectral_radiance`` at ``temperature_k`` (any shape)."""
    from .cie import spectrum_luminance

    t = check_temperature(temperature_k)
    return spectrum_luminance(lambda wl: planck_spectral_radiance(wl, t[..., None]))
