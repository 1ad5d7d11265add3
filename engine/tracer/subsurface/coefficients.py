"""A subsurface closure's medium: extinction σ_t and single-scattering albedo α from the surface albedo A
(the multiple-scattering albedo the artist picks) and the radius d (a mean free path, m), as Cycles maps them
(``subsurface_random_walk_remap``, ``bssrdf_setup_radius``).

- Random Walk: α from A by d'Eon's fit ("A Hitchhiker's Guide to Multiple Scattering", v0.3.2, Eq. 53.7,
  with van de Hulst's similarity for g): s = (4.20863 A − √(9.59217 + 41.6808 A + 17.7126 A²) + 4.09712)²,
  α = (1 − s) / (1 − g s); σ_t = 1 / d.
- Random Walk (Skin), g ≥ 0: Cycles' older polynomial fit in g (coefficients from Cycles), σ_t = 1 / (d (1 − g)),
  the radius first scaled by √(3 (1 − α')), α' the dipole albedo whose diffuse reflectance is A (Jensen's
  F_dr for the index). With g < 0 it uses d'Eon's fit too.
- α is clamped to [0, 0.999999]; below 0.2 it is raised to 0.2 and the path's weight lowered by α / 0.2
  instead (Cycles: near-black albedos would otherwise give a discontinuous, infinitely peaked walk).
"""

from __future__ import annotations

import math

from ..jit import kernel

MAX_ALPHA = 0.999999
MIN_ALPHA = 0.2
MIN_RADIUS_M = 1e-16


@kernel
def van_de_hulst_alpha(albedo, g):
    """Single-scattering albedo whose multiple-scattering albedo is ``albedo`` (d'Eon's fit, g by similarity)."""
    s = 4.20863 * albedo - math.sqrt(9.59217 + 41.6808 * albedo + 17.7126 * albedo * albedo) + 4.09712
    s *= s
    denominator = 1.0 - g * s
    alpha = (1.0 - s) / denominator if denominator != 0.0 else 0.0
    return min(max(alpha, 0.0), MAX_ALPHA)


@kernel
def _polynomial(c, g):
    value = 0.0
    power = 1.0
    for x in c:
        value += x * power
        power *= g
    return value


@kernel
def legacy_alpha(albedo, g):
    """Cycles' older fit of the single-scattering albedo (Random Walk (Skin) with g ≥ 0)."""
    a = _polynomial((1.8260523782, -1.28451056436, -1.79904629312, 9.19393289202, -22.8215585862, 32.0234874259,
                     -23.6264803333, 7.21067002658), g)
    b = 4.98511194385 + 0.127355959438 * math.exp(_polynomial(
        (0.0, 31.1491581433, -201.847017512, 841.576016723, -2018.09288505, 2731.71560286, -1935.41424244,
         559.009054474), g))
    c = _polynomial((1.09686102424, -0.394704063468, 1.05258115941, -8.83963712726, 28.8643230661, -46.8802913581,
                     38.5402837518, -12.7181042538), g)
    d = _polynomial((0.496310210422, 0.360146581622, -2.15139309747, 17.8896899217, -55.2984010333, 82.065982243,
                     -58.5106008578, 15.8478295021), g)
    e = 4.23190299701 + 0.00310603949088 * math.exp(_polynomial(
        (0.0, 76.7316253952, -594.356773233, 2448.8834203, -5576.68528998, 7116.60171912, -4763.54467887,
         1303.5318055), g))
    f = _polynomial((2.40602999408, -2.51814844609, 9.18494908356, -79.2191708682, 259.082868209, -403.613804597,
                     302.85712436, -87.4370473567), g)
    blend = albedo ** 0.25
    alpha = (1.0 - blend) * a * math.atan(b * albedo) ** c + blend * d * math.atan(e * albedo) ** f
    return min(max(alpha, 0.0), MAX_ALPHA)


@kernel
def _dipole_reflectance(alpha_prime, four_thirds_a):
    s = math.sqrt(3.0 * (1.0 - alpha_prime))
    return 0.5 * alpha_prime * (1.0 + math.exp(-four_thirds_a * s)) * math.exp(-s)


@kernel
def skin_radius_factor(albedo, ior):
    """√(3 (1 − α')) with α' the dipole albedo of diffuse reflectance ``albedo`` (bisection, as Cycles)."""
    inverse = 1.0 / ior
    f_dr = inverse * (-1.440 * inverse + 0.710) + 0.668 + 0.0636 * ior
    four_thirds_a = 4.0 / 3.0 * (1.0 + f_dr) / (1.0 - f_dr)
    if albedo < 1e-4:
        alpha_prime = 0.0
    elif albedo >= 0.995:
        alpha_prime = MAX_ALPHA
    else:
        low, high = 0.0, 1.0
        middle = 0.5
        for _ in range(12):
            middle = 0.5 * (low + high)
            if _dipole_reflectance(middle, four_thirds_a) < albedo:
                low = middle
            else:
                high = middle
        alpha_prime = middle
    return math.sqrt(3.0 * (1.0 - alpha_prime))


@kernel
def walk_coefficients(albedo, radius_m, g, skin, ior):
    """(σ_t per metre, α, weight factor) of one wavelength: ``albedo`` the surface albedo (clamped to 0-1),
    ``radius_m`` its mean free path; the factor is α / 0.2 where α was raised to 0.2, else 1."""
    albedo = min(max(albedo, 0.0), 1.0)
    if skin:
        radius_m *= skin_radius_factor(albedo, ior)
    if skin and g >= 0.0:
        alpha = legacy_alpha(albedo, g)
        sigma_t = 1.0 / (max(radius_m, MIN_RADIUS_M) * (1.0 - g))
    else:
        alpha = van_de_hulst_alpha(albedo, g)
        sigma_t = 1.0 / max(radius_m, MIN_RADIUS_M)
    factor = 1.0
    if alpha < MIN_ALPHA:
        factor = alpha / MIN_ALPHA
        alpha = MIN_ALPHA
    return sigma_t, alpha, factor
