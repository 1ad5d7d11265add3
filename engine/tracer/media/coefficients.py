"""A medium's coefficients at a path's wavelengths, and its transmittance (Beer-Lambert)."""

from __future__ import annotations

import math

from ..jit import inlined
from ..spectra.table import spectrum_value


@inlined
def extinction_at(media, spectra, medium, wavelength_nm):
    """σ_t = σ_s + σ_a (per metre) of ``medium`` at one wavelength."""
    return (spectrum_value(spectra, media.scattering[medium], wavelength_nm)
            + spectrum_value(spectra, media.absorption[medium], wavelength_nm))


@inlined
def coefficients_at(media, spectra, medium, wavelengths_nm, sigma_t, sigma_s):
    """``sigma_t[k]``, ``sigma_s[k]`` (per metre) of ``medium`` at each carried wavelength."""
    for k in range(wavelengths_nm.shape[0]):  # σ_s looked up once: it is both outputs' first term
        s = spectrum_value(spectra, media.scattering[medium], wavelengths_nm[k])
        sigma_s[k] = s
        sigma_t[k] = s + spectrum_value(spectra, media.absorption[medium], wavelengths_nm[k])


@inlined
def attenuate(media, spectra, medium, wavelengths_nm, distance_m, values):
    """``values[k]`` *= exp(-σ_t(λ_k) × distance): light crossing ``distance_m`` of ``medium``."""
    for k in range(wavelengths_nm.shape[0]):
        if values[k] == 0.0:
            continue
        sigma_t = extinction_at(media, spectra, medium, wavelengths_nm[k])
        if sigma_t > 0.0:
            values[k] *= math.exp(-sigma_t * distance_m)
