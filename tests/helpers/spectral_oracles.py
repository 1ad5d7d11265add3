"""Vectorised spectral estimators the tests use as oracles (they do not ship in the extension).

Each is written from the tracer's public pieces (CMFs, D65, Planck's law, the channels' densities), so
a test compares the compiled kernels against numpy code that shares no integration table with them.
"""

from __future__ import annotations

import numpy as np

from engine.tracer.spectra import cie
from engine.tracer.spectra.blackbody import blackbody_luminance, check_temperature, planck_spectral_radiance
from engine.tracer.spectra.rgb_to_spectrum import d65_relative_power
from engine.tracer.spectra.trapezoid import trapezoid
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID


def gaussian_channel_samples_to_rgb(radiance, wavelength_nm, pdf, channels):
    """RGB estimate for ``gaussian_rgb`` mode: one wavelength per channel.

    ``radiance``, ``wavelength_nm``, ``pdf``: [N, 3], column c sampled for
    channel c. The channel response is the channel's own truncated Gaussian
    (``channels.pdf``), so the weight is response / pdf and a constant
    spectrum of 1 gives exactly RGB (1, 1, 1). Returns [N, 3].
    """
    radiance = np.asarray(radiance, dtype=np.float64)
    pdf = np.asarray(pdf, dtype=np.float64)
    response = channels.pdf(wavelength_nm)
    safe_pdf = np.where(pdf > 0.0, pdf, 1.0)
    return np.where(pdf > 0.0, radiance * (response / safe_pdf), 0.0)


def blackbody_luminance_normalised(wavelength_nm, temperature_k):
    """Blackbody spectrum scaled to luminance Y = 1, the Y of RGB white (1, 1, 1).

    So the temperature changes the colour of a light, not its brightness.
    Broadcasts ``wavelength_nm`` against ``temperature_k``.
    """
    t = check_temperature(temperature_k)
    unique, inverse = np.unique(t, return_inverse=True)
    scale = (1.0 / blackbody_luminance(unique))[inverse].reshape(t.shape)
    return planck_spectral_radiance(wavelength_nm, t) * scale


def reflectance_spectrum_to_rgb(reflectance_fn):
    """Linear Rec.709 of a reflectance (callable of wavelength in nm -> [..., L]) under D65, white's Y = 1:
    the trapezoid of R·D65·cmf over every nanometre of 360-830 nm."""
    wavelength_nm = VISIBLE_NM_GRID
    power = d65_relative_power(wavelength_nm)
    cmf = cie.cie_xyz_cmf(wavelength_nm)
    reflectance = np.asarray(reflectance_fn(wavelength_nm), np.float64)
    xyz = trapezoid(reflectance[..., None] * (power[:, None] * cmf), wavelength_nm, axis=-2)
    return cie.xyz_to_linear_rec709(xyz / trapezoid(power * cmf[:, 1], wavelength_nm))
