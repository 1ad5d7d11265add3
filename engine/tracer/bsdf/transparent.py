"""Blender's Transparent BSDF (and Principled Alpha below 1): light passes straight through,
f = tint δ(wi = -wo). A path that takes this lobe is a null event (``SAMPLED_NULL``): nothing scattered,
so its MIS state stays that of the vertex before; shadow rays pass through with the tint as
transmittance (``materials.surface.transparency``)."""

from __future__ import annotations

import math

from ..jit import kernel
from .closure import SAMPLED_DELTA, SAMPLED_NULL, SAMPLED_TRANSMISSION


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi = -wo, inf, delta | transmission | null, 1); ``weight[k]`` = 1 (the tint is applied by
    ``dispatch``)."""
    for k in range(weight.shape[0]):
        weight[k] = 1.0
    return (-wo[0], -wo[1], -wo[2]), math.inf, SAMPLED_DELTA | SAMPLED_TRANSMISSION | SAMPLED_NULL, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """A delta lobe: nothing to evaluate."""
    f[:] = 0.0
    return 0.0
