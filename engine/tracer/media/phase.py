"""The Henyey-Greenstein phase function, as Cycles' Volume Scatter and Principled Volume use it, and a
medium's phase function whichever it is (``medium_phase_value``, ``medium_phase_sample``: Henyey-Greenstein of
the medium's anisotropy, or its table, ``tabulated_phase``).

Directions are both the way light travels: ``d_in`` the ray that arrived, ``d_out`` the one that leaves,
so g > 0 scatters forward (d_out near d_in). p(θ) = (1 - g²) / (4π (1 + g² - 2g cos θ)^1.5), cos θ =
d_in·d_out, normalised over the sphere; sampling inverts its CDF in cos θ exactly, so the weight
p / pdf is 1.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..vec3 import tangents
from .tabulated_phase import tabulated_sample, tabulated_value

#: Below this |g| the phase function is sampled as isotropic (the inverted CDF divides by g).
ISOTROPIC_G = 1e-3


@kernel
def hg_value(cos_theta, g):
    """p(θ) per steradian for cos θ = d_in·d_out."""
    denominator = 1.0 + g * g - 2.0 * g * cos_theta
    return (1.0 - g * g) / (4.0 * math.pi * denominator * math.sqrt(max(denominator, 1e-300)))


@kernel
def hg_sample(d_in, g, u1, u2):
    """(d_out, pdf): a direction drawn from p(θ) around ``d_in`` (unit), ``u1``, ``u2`` uniform in [0, 1)."""
    if abs(g) < ISOTROPIC_G:
        cos_theta = 1.0 - 2.0 * u1
    else:
        s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u1)
        cos_theta = (1.0 + g * g - s * s) / (2.0 * g)
    cos_theta = min(max(cos_theta, -1.0), 1.0)
    sin_theta = math.sqrt(max(0.0, 1.0 - cos_theta * cos_theta))
    phi = 2.0 * math.pi * u2
    t, b = tangents(d_in)
    x, y = sin_theta * math.cos(phi), sin_theta * math.sin(phi)
    d_out = (x * t[0] + y * b[0] + cos_theta * d_in[0], x * t[1] + y * b[1] + cos_theta * d_in[1],
             x * t[2] + y * b[2] + cos_theta * d_in[2])
    return d_out, hg_value(cos_theta, g)


@kernel
def medium_phase_value(media, medium, cos_theta):
    """p(θ) per steradian of row ``medium`` of ``media`` (``table.MediaArrays``)."""
    row = media.phase_row[medium]
    if row >= 0:
        return tabulated_value(media.phase_cdf, row, cos_theta)
    return hg_value(cos_theta, media.anisotropy[medium])


@kernel
def medium_phase_sample(media, medium, d_in, u1, u2):
    """(d_out, pdf) drawn from the phase function of row ``medium`` of ``media``."""
    row = media.phase_row[medium]
    if row >= 0:
        return tabulated_sample(media.phase_cdf, row, d_in, u1, u2)
    return hg_sample(d_in, media.anisotropy[medium], u1, u2)
