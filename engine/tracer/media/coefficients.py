"""A medium's coefficients at a path's wavelengths, and its transmittance (Beer-Lambert)."""

from __future__ import annotations

import math

from ..jit import inlined
from ..spectra.table import spectrum_value


@inlined
def coefficients_at(media, spectra, medium, wavelengths_nm, sigma_t, sigma_s):
    """``sigma_t[k]``, ``sigma_s[k]`` (per metre) of ``medium`` at each carried wavelength."""
    for k in range(wavelengths_nm.shape[0]):
        s = spectrum_value(spectra, media.scattering[medium], wavelengths_nm[k])
        sigma_s[k] = s
        sigma_t[k] = s + spectrum_value(spectra, media.absorption[medium], wavelengths_nm[k])


@inlined
def attenuate(media, spectra, medium, wavelengths_nm, distance_m, values):
    """``values[k]`` *= exp(-σ_t(λ_k) × distance): light crossing ``distance_m`` of ``medium``."""
    for k in range(wavelengths_nm.shape[0]):
        if values[k] == 0.0:
            continue
        lam = wavelengths_nm[k]
        sigma_t = (spectrum_value(spectra, media.scattering[medium], lam)
                   + spectrum_value(spectra, media.absorption[medium], lam))
        if sigma_t > 0.0:
            values[k] *= math.exp(-sigma_t * distance_m)
