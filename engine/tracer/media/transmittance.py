"""The transmittance of a stretch of shadow ray inside one medium: exact (Beer-Lambert) in a homogeneous
medium, estimated by ratio tracking in a grid medium (``MediaArrays.grid``, the one place the shadow stage
tells them apart)."""

from __future__ import annotations

from ..jit import inlined
from .coefficients import attenuate
from .ratio_tracking import ratio_track, ray_key


@inlined
def transmit(media, spectra, medium, wavelengths_nm, o, d, distance_m, values, sigma_t, pixel_seed, sample, layer):
    """``values[k]`` *= the transmittance of ``medium`` along ``o`` + s ``d`` (unit ``d``), s in [0,
    ``distance_m``]; ``sigma_t`` scratch [K]; the path's ``pixel_seed`` and ``sample`` and the shadow ray's
    ``layer`` seed ratio tracking's numbers."""
    if media.grid[medium] >= 0:
        ratio_track(media, spectra, medium, wavelengths_nm, o, d, distance_m, values, sigma_t, pixel_seed, sample,
                    ray_key(layer, o))
    else:
        attenuate(media, spectra, medium, wavelengths_nm, distance_m, values)
