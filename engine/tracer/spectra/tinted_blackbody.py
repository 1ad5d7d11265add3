"""Planck's spectrum filtered by an RGB tint, on the 1 nm grid: the light of Blender's Temperature × Color
on a light (Cycles multiplies the light's colour by the temperature's colour) and of a Principled Volume's
Blackbody Tint.

The tint acts as a reflectance of its colour would (a surface of that colour lit by the blackbody); a tint
above 1 scales the spectrum by its largest component, so (2, 2, 2) is twice as bright and white (1, 1, 1) leaves
the luminance-1 Planck spectrum exactly as it is.
"""

from __future__ import annotations

import numpy as np

from .blackbody import MAX_TEMPERATURE_K, MIN_TEMPERATURE_K, blackbody_luminance, planck_spectral_radiance
from .wavelengths import VISIBLE_NM_GRID

WHITE = (1.0, 1.0, 1.0)


def reflectance_on_grid(rgb) -> np.ndarray:
    """The reflectance spectrum Prism upsamples from linear Rec.709 ``rgb`` (values clamped to 0-1), on
    the 1 nm grid of ``wavelengths.VISIBLE_NM_GRID``: the spectrum surfaces of that colour reflect."""
    from .rgb_to_spectrum import reflectance_coefficients

    rgb = np.clip(np.asarray(rgb, dtype=np.float64), 0.0, 1.0)
    if rgb[0] == rgb[1] == rgb[2] and rgb[0] in (0.0, 1.0):
        return np.full(len(VISIBLE_NM_GRID), float(rgb[0]))
    c0, c1, c2 = reflectance_coefficients(rgb)
    lam = np.asarray(VISIBLE_NM_GRID, dtype=np.float64)
    u = np.clip((c0 * lam + c1) * lam + c2, -1e10, 1e10)
    return 0.5 + 0.5 * u / np.sqrt(1.0 + u * u)


def tint_on_grid(tint) -> np.ndarray:
    """The filter a tint applies: ``s`` × the reflectance of ``tint / s``, s = max(largest component, 1)."""
    rgb = np.maximum(np.asarray(tint, dtype=np.float64), 0.0)
    scale = max(float(rgb.max()), 1.0)
    return scale * reflectance_on_grid(rgb / scale)


def tinted_blackbody(temperature_k, tint) -> np.ndarray:
    """[len(T), len(VISIBLE_NM_GRID)]: the luminance-1 Planck spectrum at each temperature (clamped to
    1000-40000 K) filtered by ``tint``."""
    shown = np.clip(np.atleast_1d(np.asarray(temperature_k, dtype=np.float64)), MIN_TEMPERATURE_K, MAX_TEMPERATURE_K)
    lam = np.asarray(VISIBLE_NM_GRID, dtype=np.float64)
    planck = planck_spectral_radiance(lam[None, :], shown[:, None]) / blackbody_luminance(shown)[:, None]
    return tint_on_grid(tint)[None, :] * planck
