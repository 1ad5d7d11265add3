"""Principled Hair BSDF, Chiang model: Chiang, Bitterli, Tappan & Burley, "A Practical and Controllable Hair and
Fur Model for Production Path Tracing" (EGSR 2016), as Cycles 4.5 computes it
(``kernel/closure/bsdf_principled_hair_chiang.h``), per wavelength.

Directions are in the fibre's frame (X = the curve tangent; Y ⟂ X and the view; Z = X × Y): sin θ is a
direction's X component and φ its angle in the (Y, Z) plane. ``h`` (-1..1) is where the view ray met the fibre
across its width. Light leaves after p = 0 (R: reflected at the cuticle), 1 (TT: through the fibre), 2 (TRT:
reflected once inside) internal paths, plus a residual lobe for everything after (TRRT+, longitudinally the
view's own cone, azimuthally uniform). Each lobe is Ap(λ) Mp(θi) Np(φ):

- Ap: Fresnel f at cos θo cos γo and the fibre's transmittance T(λ) = exp(-σa(λ) 2 cos γt / cos θt), with
  A0 = f, A1 = (1-f)² T, A2 = A1 T f, A3 = A2 T f / (1 - T f). Without absorption they sum to 1.
- Mp: d'Eon et al.'s longitudinal lobe (EGSR 2011) of variance v about the view's cone tilted by the cuticle
  angle α (R: -2α, TT: α, TRT: 4α, Cycles' signs), with the log form below v = 0.1. Normalised over d(sin θi).
- Np: a logistic of scale s in φ about Δφ_p = 2pγt - 2γo + pπ, trimmed to [-π, π] and renormalised.

The value Cycles returns, F = Σ Ap Mp Np, is f |cos θ| for the fibre (dω = d(sin θ) dφ): the functions here
return F; ``bsdf.hair`` divides by the material's cosine. Sampling picks a lobe by its Ap averaged over the
path's wavelengths (Cycles: the Ap's grey value) and samples Mp (d'Eon's exact inversion) and Np (the
trimmed logistic's inverse CDF) exactly, so the pdf is Σ Ā_p Mp Np.

Where Prism differs from Cycles, on purpose:
- I0 is summed until its series converges (Cycles stops after 10 terms: up to 2 % low near x = 12, the
  switch to its asymptotic log form, which Prism keeps).
- The R lobe is sampled with its own variance (Coat's m0); Cycles samples it with v and weights the sample by
  eval / pdf with m0 in the pdf, which is biased when Coat > 0. With Coat 0 both are the same.
"""

from __future__ import annotations

import math

from ..jit import kernel
from .optics import fresnel_dielectric

SQRT_PI_OVER_8 = math.sqrt(math.pi / 8.0)
MIN_ROUGHNESS = 0.001  # Cycles clamps every hair roughness to [0.001, 1] (``bsdf_hair_chiang_setup``)
LOG_FORM_VARIANCE = 0.1  # below this longitudinal variance Mp is evaluated in log space (Cycles)
LOG_BESSEL_ASYMPTOTIC = 12.0  # above this argument log I0 uses its asymptotic expansion (Cycles)
MIN_LOBE_RANDOM = 1e-5  # Cycles' floor on the random number that samples Mp (keeps log() finite)


@kernel
def clamp_roughness(r):
    return min(max(r, MIN_ROUGHNESS), 1.0)


@kernel
def longitudinal_variance(roughness):
    """Mp's variance v for a (clamped) Blender roughness: Chiang et al.'s fit (their eq. 7), as Cycles maps it."""
    r = roughness
    return (0.726 * r + 0.812 * r * r + 3.700 * r ** 20) ** 2


@kernel
def azimuthal_scale(radial_roughness):
    """Np's logistic scale s for a (clamped) radial roughness (Chiang et al. eq. 8, times √(π/8) as Cycles)."""
    r = radial_roughness
    return (0.265 * r + 1.194 * r * r + 5.372 * r ** 22) * SQRT_PI_OVER_8


@kernel
def albedo_roughness_scale(radial_roughness):
    """Cycles' ``bsdf_principled_hair_albedo_roughness_scale``: Chiang et al.'s fit of ln(albedo) / √σa."""
    x = radial_roughness
    return (((((0.245 * x) + 5.574) * x - 10.73) * x + 2.532) * x - 0.215) * x + 5.969


@kernel
def sigma_from_reflectance(reflectance, radial_roughness):
    """Absorption (per fibre diameter) that gives a fibre of this colour: (ln c / scale(radial))² (Cycles'
    ``bsdf_principled_hair_sigma_from_reflectance``); a black colour absorbs everything it can (c floored)."""
    c = max(reflectance, 1e-30)
    x = math.log(c) / albedo_roughness_scale(radial_roughness)
    return x * x


@kernel
def bessel_i0(x):
    """Modified Bessel function of the first kind, order 0, by its power series (to convergence)."""
    q = 0.25 * x * x
    term = 1.0
    total = 1.0
    for i in range(1, 200):
        term *= q / (i * i)
        total += term
        if term < 1e-17 * total:
            break
    return total


@kernel
def log_bessel_i0(x):
    if x > LOG_BESSEL_ASYMPTOTIC:
        return x + 0.5 * (1.0 / (8.0 * x) - math.log(2.0 * math.pi) - math.log(x))
    return math.log(bessel_i0(x))


@kernel
def longitudinal(sin_i, cos_i, sin_o, cos_o, v):
    """Mp (per unit sin θi) for variance ``v`` (d'Eon et al. 2011; Cycles' ``longitudinal_scattering``)."""
    inv_v = 1.0 / v
    cos_arg = cos_i * cos_o * inv_v
    sin_arg = sin_i * sin_o * inv_v
    if v <= LOG_FORM_VARIANCE:
        return math.exp(log_bessel_i0(cos_arg) - sin_arg - inv_v + 0.6931 + math.log(0.5 * inv_v))
    return math.exp(-sin_arg) * bessel_i0(cos_arg) / (math.sinh(inv_v) * 2.0 * v)


@kernel
def _logistic(x, s):
    e = math.exp(-abs(x) / s)
    return e / (s * (1.0 + e) ** 2)


@kernel
def _logistic_cdf(x, s):
    arg = -x / s
    if arg > 88.0:
        return 0.0
    return 1.0 / (1.0 + math.exp(arg))


@kernel
def trimmed_logistic(x, s):
    """The logistic of scale ``s`` restricted to [-π, π] and renormalised there."""
    norm = 1.0 - 2.0 * _logistic_cdf(-math.pi, s)
    return _logistic(x, s) / norm if norm > 0.0 else 0.0


@kernel
def sample_trimmed_logistic(u, s):
    low = _logistic_cdf(-math.pi, s)
    x = -s * math.log(1.0 / (u * (1.0 - 2.0 * low) + low) - 1.0)
    return min(max(x, -math.pi), math.pi)


@kernel
def delta_phi(p, gamma_o, gamma_t):
    return 2.0 * p * gamma_t - 2.0 * gamma_o + p * math.pi


@kernel
def wrap_angle(a):
    """``a`` in [-π, π]."""
    return (a + math.pi) - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi)) - math.pi


@kernel
def tilted_cone(sin_o, cos_o, alpha, p):
    """(sin, cos) of the view's cone tilted for lobe ``p`` (0 R, 1 TT, 2 TRT) by Cycles' cuticle angle ``alpha``
    (the node's Offset, negated: ``bsdf_hair_chiang_setup``); the residual lobe (p = 3) is not tilted."""
    if p == 3:
        return sin_o, cos_o
    a = alpha * (-2.0 if p == 0 else (1.0 if p == 1 else 4.0))
    sa, ca = math.sin(a), math.cos(a)
    # Cycles: R (sin_o cos 2α - cos_o sin 2α), TT (sin_o cos α + cos_o sin α), TRT (sin_o cos 4α + cos_o sin 4α)
    return sin_o * ca + cos_o * sa, abs(cos_o * ca - sin_o * sa)


@kernel
def lobe_variance(v, m0, p):
    """Mp's variance for lobe ``p``: m0 (R, Coat-scaled), v/4 (TT), 4v (TRT and residual)."""
    if p == 0:
        return m0
    return 0.25 * v if p == 1 else 4.0 * v


@kernel
def fibre_geometry(sin_o, h, eta):
    """(cos θo, γo, γt, cos γt / cos θt factor 2 cos γt / cos θt, Fresnel f) of the view seen at ``sin_o``
    meeting the fibre at ``h``."""
    cos_o = math.sqrt(max(0.0, 1.0 - sin_o * sin_o))
    sin_t = sin_o / eta
    cos_t = math.sqrt(max(0.0, 1.0 - sin_t * sin_t))
    sin_gamma_o = min(max(h, -1.0), 1.0)
    cos_gamma_o = math.sqrt(max(0.0, 1.0 - sin_gamma_o * sin_gamma_o))
    gamma_o = math.asin(sin_gamma_o)
    sin_gamma_t = min(max(sin_gamma_o * cos_o / math.sqrt(max(eta * eta - sin_o * sin_o, 1e-12)), -1.0), 1.0)
    cos_gamma_t = math.sqrt(max(0.0, 1.0 - sin_gamma_t * sin_gamma_t))
    gamma_t = math.asin(sin_gamma_t)
    path = 2.0 * cos_gamma_t / cos_t if cos_t > 0.0 else math.inf
    f = fresnel_dielectric(cos_o * cos_gamma_o, eta)
    return cos_o, gamma_o, gamma_t, path, f


@kernel
def attenuation(f, transmittance, p):
    """Ap for one wavelength whose transmittance through the fibre is ``transmittance``."""
    if p == 0:
        return f
    a = (1.0 - f) * (1.0 - f) * transmittance
    if p == 1:
        return a
    a *= transmittance * f
    if p == 2:
        return a
    tf = transmittance * f
    return a * tf / (1.0 - tf) if tf < 1.0 else 0.0


@kernel
def lobe_shares(f, path, sigma, hero, collapsed):
    """Sampling probabilities of the four lobes: their Ap averaged over the path's wavelengths (the hero alone
    once the path is collapsed to it), normalised; a tuple of 4."""
    a0 = a1 = a2 = a3 = 0.0
    count = 0
    for k in range(sigma.shape[0]):
        if collapsed and k != hero:
            continue
        t = math.exp(-sigma[k] * path)
        a0 += attenuation(f, t, 0)
        a1 += attenuation(f, t, 1)
        a2 += attenuation(f, t, 2)
        a3 += attenuation(f, t, 3)
        count += 1
    total = a0 + a1 + a2 + a3
    if not total > 0.0:
        return 1.0, 0.0, 0.0, 0.0
    return a0 / total, a1 / total, a2 / total, a3 / total


@kernel
def chiang_value(sin_i, phi, sin_o, h, eta, alpha, v, s, m0, sigma, hero, collapsed, out):
    """``out[k]`` = F = Σ Ap Mp Np at each wavelength (absorption ``sigma[k]`` per fibre diameter) for light from
    (``sin_i``, azimuth ``phi`` from the view's); returns the pdf of ``chiang_sample`` (solid angle)."""
    cos_o, gamma_o, gamma_t, path, f = fibre_geometry(sin_o, h, eta)
    cos_i = math.sqrt(max(0.0, 1.0 - sin_i * sin_i))
    share = lobe_shares(f, path, sigma, hero, collapsed)
    mn = (0.0, 0.0, 0.0, 0.0)
    pdf = 0.0
    for p in range(4):
        so, co = tilted_cone(sin_o, cos_o, alpha, p)
        mp = longitudinal(sin_i, cos_i, so, co, lobe_variance(v, m0, p))
        if p < 3:
            np_ = trimmed_logistic(wrap_angle(phi - delta_phi(p, gamma_o, gamma_t)), s)
        else:
            np_ = 0.5 / math.pi
        mn = (mp * np_ if p == 0 else mn[0], mp * np_ if p == 1 else mn[1], mp * np_ if p == 2 else mn[2],
              mp * np_ if p == 3 else mn[3])
        pdf += share[p] * mp * np_
    for k in range(out.shape[0]):
        t = math.exp(-sigma[k] * path)
        out[k] = (attenuation(f, t, 0) * mn[0] + attenuation(f, t, 1) * mn[1] + attenuation(f, t, 2) * mn[2]
                  + attenuation(f, t, 3) * mn[3])
    return pdf


@kernel
def chiang_sample(sin_o, h, eta, alpha, v, s, m0, sigma, hero, collapsed, u0, u1, u2):
    """(sin θi, φ from the view's azimuth, lobe p): a direction drawn from the lobes (``u0`` picks the lobe and,
    rescaled, θi; ``u1`` the cone's azimuth; ``u2`` φ)."""
    cos_o, gamma_o, gamma_t, path, f = fibre_geometry(sin_o, h, eta)
    share = lobe_shares(f, path, sigma, hero, collapsed)
    p = 0
    u = u0
    while p < 3 and not u < share[p]:
        u -= share[p]
        p += 1
    u = min(u / share[p], 1.0) if share[p] > 0.0 else 0.5
    u = max(u, MIN_LOBE_RANDOM)
    var = lobe_variance(v, m0, p)
    so, co = tilted_cone(sin_o, cos_o, alpha, p)
    fac = 1.0 + var * math.log(u + (1.0 - u) * math.exp(-2.0 / var))
    sin_i = -fac * so + math.sqrt(max(0.0, 1.0 - fac * fac)) * math.cos(2.0 * math.pi * u1) * co
    sin_i = min(max(sin_i, -1.0), 1.0)
    if p < 3:
        phi = delta_phi(p, gamma_o, gamma_t) + sample_trimmed_logistic(u2, s)
    else:
        phi = 2.0 * math.pi * u2
    return sin_i, phi, p
