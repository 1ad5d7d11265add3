"""Lambertian transmission (Blender's Translucent BSDF): f = albedo(λ) / π on the far side of the
surface (``spectral[0]``), cosine-weighted sampling there. As Cycles' (``bsdf_diffuse.h``), it does not ask on
which side of the normal the view is."""

from __future__ import annotations

import math

from ..jit import kernel
from ..warps import cosine_hemisphere
from .closure import SAMPLED_TRANSMISSION


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = f |cos wi| / pdf."""
    wi = cosine_hemisphere(u1, u2)
    if wi[2] <= 0.0:
        weight[:] = 0.0
        return (wi[0], wi[1], -wi[2]), 0.0, SAMPLED_TRANSMISSION, 1.0
    for k in range(weight.shape[0]):
        weight[k] = spectral[0, k]
    return (wi[0], wi[1], -wi[2]), wi[2] / math.pi, SAMPLED_TRANSMISSION, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` (without the cosine); returns the pdf of ``sample`` for ``wi``."""
    if wi[2] >= 0.0:
        f[:] = 0.0
        return 0.0
    for k in range(f.shape[0]):
        f[k] = spectral[0, k] / math.pi
    return -wi[2] / math.pi
