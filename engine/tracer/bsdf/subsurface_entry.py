"""The entry bounce of a subsurface closure (Cycles' ``subsurface_entry_bounce``): the direction a path takes
into the surface before its random walk (``subsurface.walk``). It is not a BSDF: it evaluates to 0 (light
sampling and the other closures' MIS never see it), and a sample has weight 1 before the closure's tint, as
Cycles skips the refraction's shadowing and Fresnel terms here ("we only care about the directional
distribution"): the walk and the exit's Lambertian lobe carry the light.

Random Walk: a GGX microfacet normal of the closure's alpha drawn from the visible normals, and the view
refracted through it with index ``C_ETA`` (clamped to 1.01-3.8, so no total internal reflection). Random
Walk (Skin): half the samples enter cosine-weighted, the others refract through microfacets of alpha 1.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..warps import cosine_hemisphere
from .closure import (C_ALPHA, C_ETA, C_SSS_METHOD, SAMPLED_DELTA, SAMPLED_SUBSURFACE, SAMPLED_TRANSMISSION,
                      SSS_SKIN)
from .microfacet import sample_visible_normal

#: Cycles' bounds on a subsurface closure's index (``bssrdf_setup``).
MIN_IOR, MAX_IOR = 1.01, 3.8
#: The flags of an entry sample: a delta event (no pdf to weigh against), through the surface.
ENTRY = SAMPLED_SUBSURFACE | SAMPLED_DELTA | SAMPLED_TRANSMISSION


@kernel
def entry_direction(row, wo, u0, u1, u2):
    """(wi, valid): the direction into the surface (local frame, z < 0 for a view with z > 0)."""
    alpha = row[C_ALPHA]
    if row[C_SSS_METHOD] == SSS_SKIN:
        if u0 < 0.5:
            wi = cosine_hemisphere(u1, u2)
            return (wi[0], wi[1], -wi[2]), wi[2] > 0.0
        alpha = 1.0
    if wo[2] <= 0.0:
        return (0.0, 0.0, -1.0), False
    h = sample_visible_normal(wo, max(alpha, 1e-4), u1, u2)
    inverse_eta = 1.0 / min(max(row[C_ETA], MIN_IOR), MAX_IOR)
    cos_h = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]
    root = math.sqrt(max(1.0 - inverse_eta * inverse_eta * (1.0 - cos_h * cos_h), 1e-14))
    along = inverse_eta * cos_h - root
    wi = (-inverse_eta * wo[0] + along * h[0], -inverse_eta * wo[1] + along * h[1], -inverse_eta * wo[2] + along * h[2])
    return wi, wi[2] < 0.0


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = 1 (0 where no direction into the surface)."""
    wi, valid = entry_direction(row, wo, u0, u1, u2)
    weight[:] = 1.0 if valid else 0.0
    return wi, 1.0 if valid else 0.0, ENTRY, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """0: the closure's light comes through its random walk, not through evaluation."""
    f[:] = 0.0
    return 0.0
