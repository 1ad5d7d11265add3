"""The phase functions of Blender's Volume Scatter node besides Henyey-Greenstein (Fournier-Forand, Draine,
Rayleigh, Mie), as densities per steradian of cos θ (θ between the ray that arrives and the one that leaves),
with Cycles 4.5's parameters and clamps (``kernel/closure/volume_*.h``), and the table the kernels sample
them from (``tabulated_phase``).

- Rayleigh: 3 (1 + cos² θ) / (16 π) (Frisvad 2011, JOSA A 28(12)).
- Draine (2003, ApJ 598): (1 − g²)(1 + α cos² θ) / ((1 + α (1 + 2 g²) / 3) 4π (1 + g² − 2 g cos θ)^1.5), g
  clamped to |g| ≤ 1 − 10⁻³ as Cycles.
- Fournier-Forand (1994, 1999) of particle IOR n and backscatter fraction B (B clamped to 0.5 − 10⁻³, n to ≥
  1 + 10⁻³): δ = 4 sin²(θ/2) / (3 (n − 1)²), ν from B, and Cycles' normalised form.
- Mie for water droplets of diameter d (µm): the mixture (1 − w) HG(g_HG) + w Draine(g_D, α) of Jendersie and
  d'Eon 2023, "An approximate Mie scattering function for fog and cloud rendering", whose fitted parameters
  (their eqs. 7-22) Cycles uses; HG's g clamped as Cycles clamps it.

A medium's phase is a list of lobes (weight, kind, parameters), a mixture; ``phase_table`` integrates it over
the bins of ``tabulated_phase`` into a CDF.
"""

from __future__ import annotations

import math

import numpy as np

from .tabulated_phase import bin_edges

HENYEY_GREENSTEIN, FOURNIER_FORAND, DRAINE, RAYLEIGH, MIE = ("HENYEY_GREENSTEIN", "FOURNIER_FORAND", "DRAINE",
                                                              "RAYLEIGH", "MIE")
#: Cycles' clamp of g (HG and Draine): a delta lobe has no density.
MAX_G = 1.0 - 1e-3


def _clamp_g(g):
    return math.copysign(min(abs(g), MAX_G), g)


def henyey_greenstein(cos_theta, g):
    g = _clamp_g(g)
    denominator = 1.0 + g * g - 2.0 * g * cos_theta
    return (1.0 - g * g) / (4.0 * math.pi * denominator * np.sqrt(denominator))


def rayleigh(cos_theta):
    return 3.0 * (1.0 + cos_theta * cos_theta) / (16.0 * math.pi)


def draine(cos_theta, g, alpha):
    g = _clamp_g(g)
    denominator = 1.0 + g * g - 2.0 * g * cos_theta
    return ((1.0 - g * g) * (1.0 + alpha * cos_theta * cos_theta)
            / ((1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0) * 4.0 * math.pi * denominator * np.sqrt(denominator)))


def _ff_delta(n, sin_half_sq):
    return 4.0 * sin_half_sq / (3.0 * (n - 1.0) ** 2)


def fournier_forand(cos_theta, backscatter, ior):
    """Cycles' Fournier-Forand density (its ``phase_fournier_forand``), B and n clamped as Cycles clamps them."""
    b = min(abs(backscatter), 0.5 - 1e-3)
    n = max(ior, 1.0 + 1e-3)
    d90, d180 = _ff_delta(n, 0.5), _ff_delta(n, 1.0)
    v = -math.log(2.0 * b * (d90 - 1.0) + 1.0) / math.log(d90)
    coefficient = (d180 ** -v - 1.0) / (d180 - 1.0) / (16.0 * math.pi)
    cos_theta = np.asarray(cos_theta, dtype=np.float64)
    s = 0.5 * (1.0 - cos_theta)
    delta = _ff_delta(n, s)
    m_delta = 1.0 - delta
    near = np.abs(m_delta) < 1e-3
    safe = np.where(near, 0.5, m_delta)
    power = np.power(np.where(near, 0.5, delta), v)
    s_safe = np.maximum(s, 1e-300)
    general = (v * safe - (1.0 - power) + (np.where(near, 0.5, delta) * (1.0 - power) - v * safe) / s_safe) / (
        4.0 * math.pi * safe * safe * power)
    # δ near 1 (θ where δ crosses 1): Cycles' first-order expansion, which is continuous there.
    taylor = v * ((v - 1.0) - (v + 1.0) / s_safe) / (8.0 * math.pi) + v * (v + 1.0) * m_delta * (
        2.0 * (v - 1.0) - (2.0 * v + 1.0) / s_safe) / (24.0 * math.pi)
    value = np.where(near, taylor, general) + coefficient * (3.0 * cos_theta * cos_theta - 1.0)
    return np.where(np.abs(cos_theta) >= 1.0, 0.0, value)


def mie_parameters(d):
    """(g_HG, g_D, α, w) of Jendersie and d'Eon's fit for droplets of diameter ``d`` µm (clamped at 0)."""
    d = max(float(d), 0.0)
    if d <= 0.1:
        return 13.8 * d * d, 1.1456 * d * math.sin(9.29044 * d), 250.0, 0.252977 - 312.983 * d ** 4.3
    if d < 1.5:
        log_d = math.log(d)
        a = (log_d - 0.238604) * (log_d + 1.00667)
        b = 0.507522 - 0.15677 * log_d
        c = 1.19692 * math.cos(a / b) + 1.37932 * log_d + 0.0625835
        return (0.862 - 0.143 * log_d * log_d, 0.379685 * math.cos(c) + 0.344213, 250.0,
                0.146209 * math.cos(3.38707 * log_d + 2.11193) + 0.316072 + 0.0778917 * log_d)
    if d < 5.0:
        log_d = math.log(d)
        temp = math.cos(5.68947 * (math.log(log_d) - 0.0292149))
        g_d = 0.500411 - 0.081287 / (-2.0 * log_d + math.tan(log_d) + 1.27551)
        w = 0.026914 * (log_d - temp) + 0.3764
        return 0.0604931 * math.log(log_d) + 0.940256, g_d, 7.30354 * log_d + 6.31675, w
    return (math.exp(-0.0990567 / (d - 1.67154)), math.exp(-2.20679 / (d + 3.91029) - 0.428934),
            math.exp(3.62489 - 8.29288 / (d + 5.52825)), math.exp(-0.599085 / (d - 0.641583) - 0.665888))


def lobe_density(cos_theta, kind, parameters):
    """The density per steradian of one lobe (``kind`` one of the names above) at ``cos_theta``."""
    if kind == HENYEY_GREENSTEIN:
        return henyey_greenstein(cos_theta, *parameters)
    if kind == RAYLEIGH:
        return rayleigh(cos_theta)
    if kind == DRAINE:
        return draine(cos_theta, *parameters)
    if kind == FOURNIER_FORAND:
        return fournier_forand(cos_theta, *parameters)
    if kind == MIE:
        g_hg, g_d, alpha, w = mie_parameters(*parameters)
        return (1.0 - w) * henyey_greenstein(cos_theta, g_hg) + w * draine(cos_theta, g_d, alpha)
    raise ValueError(f"unknown phase function {kind!r}")


def mixture_density(cos_theta, lobes):
    """The density of the mixture of ``lobes`` ((weight, kind, parameters), weights summing to any w > 0)."""
    total = sum(w for w, _, _ in lobes)
    return sum(w * lobe_density(cos_theta, kind, parameters) for w, kind, parameters in lobes) / total


# Gauss-Legendre nodes per bin, in log(1 - cos θ): the densities are smooth there, even Fournier-Forand's
# forward peak, which is a power of 1 - cos θ.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(8)


def phase_table(lobes) -> np.ndarray:
    """float64 [BINS + 1]: the CDF of the mixture ``lobes`` over ``tabulated_phase``'s bins (from cos θ = 1
    down to -1), starting at 0 and ending at exactly 1. Each bin's probability is 2π ∫ p d(cos θ) over it; the
    first bin, from 1 - cos θ = 0 to its first edge, takes what the others leave (each density is normalised)."""
    edges = bin_edges()  # 1 - cos θ, increasing from 0 to 2
    low, high = np.log(edges[1:-1]), np.log(edges[2:])
    half = 0.5 * (high - low)
    s = (low + high)[:, None] * 0.5 + half[:, None] * _NODES[None, :]
    t = np.exp(s)
    density = mixture_density(1.0 - t, lobes)
    probability = 2.0 * math.pi * np.sum(density * t * _WEIGHTS[None, :], axis=1) * half
    probability = np.maximum(probability, 0.0)
    first = max(1.0 - probability.sum(), 0.0)
    cdf = np.concatenate([[0.0, first], first + np.cumsum(probability)])
    return cdf / cdf[-1]
