"""Lambertian reflection: f = albedo(λ) / π (``spectral[0]``), cosine-weighted sampling.

As in Cycles (``bsdf_diffuse.h``), only the light's side of the normal matters: a view from behind a bumped or
smoothed normal still sees the surface lit (the stages check the geometric side of sampled directions)."""

from __future__ import annotations

import math

from ..jit import kernel
from ..warps import cosine_hemisphere


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = f |cos wi| / pdf."""
    wi = cosine_hemisphere(u1, u2)
    if wi[2] <= 0.0:
        weight[:] = 0.0
        return wi, 0.0, 0, 1.0
    for k in range(weight.shape[0]):
        weight[k] = spectral[0, k]
    return wi, wi[2] / math.pi, 0, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` (without the cosine); returns the pdf of ``sample`` for ``wi``."""
    if wi[2] <= 0.0:
        f[:] = 0.0
        return 0.0
    for k in range(f.shape[0]):
        f[k] = spectral[0, k] / math.pi
    return wi[2] / math.pi
