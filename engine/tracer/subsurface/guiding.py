"""Dwivedi-guided directions and distances for the random walk (``walk``), as Cycles samples them.

A walk in a medium of high albedo wanders long before it finds the surface again. Guiding proposes, besides
phase sampling, directions that lean toward the entry surface's outward normal n and longer flights along
them, from the zero-variance analysis of a half-space (Křivánek & d'Eon 2014, "A zero-variance-based sampling
scheme for Monte Carlo subsurface scattering"; Meng, Hanika & Dachsbacher 2016, "Improving the Dwivedi
sampling scheme", Eq. 9-10; d'Eon & Křivánek 2020, "Zero-variance theory for efficient subsurface
scattering", Eq. 67 for the diffusion length):

- the diffusion length ν(α) = 1 / √(1 − α^(2.44294 − 0.0215813 α + 0.578637 / α)) (> 1);
- the direction's cosine μ = ω·n has the density 1 / ((ν − μ) ln((ν + 1) / (ν − 1))) on [−1, 1] (azimuth
  uniform), so per steradian p(ω) = that / 2π; drawn by inverting its CDF: μ = ν − (ν + 1) ((ν − 1) / (ν +
  1))^u;
- the flight along ω is drawn with the extinction stretched to σ_t (1 − μ / ν) (longer toward the surface).

Each step after the first is guided with probability ``guided_fraction`` (Cycles' heuristic: 1 − max(0.5,
|g|^(1/8)), 0.75 past the similarity level) and weighted by the balance heuristic over both strategies and
every carried wavelength. Cycles' backward guiding (toward an opposite surface found by the first flight) is
not done.
"""

from __future__ import annotations

import math

from ..jit import inlined, kernel
from ..vec3 import tangents

#: The guided share of steps once the walk scatters isotropically (past ``walk.SIMILARITY_STEPS``).
ISOTROPIC_GUIDED_FRACTION = 0.75


@kernel
def diffusion_length(alpha):
    """ν(α) for a single-scattering albedo 0 < α < 1."""
    return 1.0 / math.sqrt(1.0 - alpha ** (2.44294 - 0.0215813 * alpha + 0.578637 / alpha))


@kernel
def guided_fraction(g, similar):
    """The probability that a step is guided, for the walk's anisotropy ``g``."""
    if similar:
        return ISOTROPIC_GUIDED_FRACTION
    return 1.0 - max(0.5, abs(g) ** 0.125)


@kernel
def guided_cosine(nu, log_ratio, u):
    """μ = ω·n drawn from the guided density; ``log_ratio`` = ln((ν + 1) / (ν − 1))."""
    return min(max(nu - (nu + 1.0) * math.exp(-u * log_ratio), -1.0), 1.0)


@kernel
def guided_pdf(nu, log_ratio, mu):
    """The guided density of a direction per steradian, at μ = ω·n."""
    return 1.0 / (2.0 * math.pi * (nu - mu) * log_ratio)


@inlined
def guided_direction(n, mu, u):
    """The unit direction at cosine ``mu`` to unit ``n`` and azimuth 2π ``u``."""
    s, t = tangents(n)
    sine = math.sqrt(max(0.0, 1.0 - mu * mu))
    x, y = sine * math.cos(2.0 * math.pi * u), sine * math.sin(2.0 * math.pi * u)
    return (x * s[0] + y * t[0] + mu * n[0], x * s[1] + y * t[1] + mu * n[1], x * s[2] + y * t[2] + mu * n[2])
