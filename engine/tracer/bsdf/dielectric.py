"""Dielectric interfaces (glass): smooth (delta) or rough GGX, optionally under a thin-film coating.

The local +Z is the outward normal: wo.z > 0 arrives from outside (index 1), wo.z < 0 from inside.
``eta`` is the glass index: at the path's hero wavelength when the glass disperses (the path then
carries only its hero), else the constant index. Refracted radiance is scaled by 1/eta'² (radiance is
not symmetric under refraction, Veach 1997 §5.2). Reflection or refraction is chosen with probability
p = reflected / (reflected + transmitted) over the carried wavelengths (the hero's once collapsed; the
mean reflectance for untinted glass), each column weighted R_k / p or T_k / (1 - p). Tints (Blender's
Specular Tint scales F0, a transmission tint scales T) come in ``spectral[0]`` and ``spectral[1]``.
Rough transmission follows Walter et al. 2007 with visible-normal sampling (Heitz 2018).
"""

from __future__ import annotations

import math

from ..jit import kernel
from .closure import (C_ALPHA, C_COAT_IOR, C_COAT_NM, C_FRESNEL, C_S1, C_SPECTRUM, GLASS, REFRACTION_ONLY, SAMPLED_DELTA,
                      SAMPLED_TRANSMISSION, SMOOTH_ALPHA)
from .microfacet import ggx_d, ggx_g1, ggx_g2, reflect, sample_visible_normal, visible_normal_pdf
from .optics import dielectric_f0, fresnel_dielectric, refract, thin_film_reflectance, tinted_fresnel


@kernel
def untinted(row):
    """Plain glass: no F0 tint, no transmission tint (the common case, kept fast)."""
    return row[C_SPECTRUM] == -1.0 and row[C_S1] == -1.0 and int(row[C_FRESNEL]) == GLASS


@kernel
def interface_reflectance(row, spectral, eta, cos_i, wavelength_nm, out):
    """``out[k]`` = reflectance for signed ``cos_i`` (< 0: from inside) at every carried wavelength
    (0 for a refraction-only closure), F0 tinted by ``spectral[0]``."""
    if int(row[C_FRESNEL]) == REFRACTION_ONLY:
        for k in range(out.shape[0]):
            out[k] = 0.0
        return
    plain = row[C_SPECTRUM] == -1.0
    f0_real = dielectric_f0(eta)
    if row[C_COAT_NM] <= 0.0:
        r = fresnel_dielectric(cos_i, eta)
        for k in range(out.shape[0]):
            out[k] = r if plain else tinted_fresnel(r, f0_real, spectral[0, k], False)
        return
    n_in, n_out = (1.0, eta) if cos_i >= 0.0 else (eta, 1.0)
    for k in range(out.shape[0]):
        r = thin_film_reflectance(cos_i, wavelength_nm[k], row[C_COAT_NM], n_in, row[C_COAT_IOR], complex(n_out, 0.0))
        out[k] = r if plain else tinted_fresnel(r, f0_real, spectral[0, k], True)


@kernel
def transmittance(row, spectral, reflectance, k, tir):
    """Transmitted fraction at column ``k`` (``reflectance`` as ``interface_reflectance`` gave it)."""
    if tir:
        return 0.0
    if int(row[C_FRESNEL]) == REFRACTION_ONLY:
        return spectral[1, k]
    return (1.0 - reflectance[k]) * spectral[1, k]


@kernel
def choice_probability(reflectance, hero, collapsed):
    """Probability of reflecting: the hero's reflectance once collapsed, else the mean over columns."""
    if collapsed:
        p = reflectance[hero]
    else:
        p = 0.0
        for k in range(reflectance.shape[0]):
            p += reflectance[k]
        p /= reflectance.shape[0]
    return min(max(p, 0.0), 1.0)


@kernel
def reflect_probability(row, spectral, reflectance, hero, collapsed, tir):
    """Probability of reflecting: reflected / (reflected + transmitted) over the carried wavelengths (the
    hero's once collapsed). Equals the mean reflectance for untinted glass."""
    if untinted(row) and not tir:
        return choice_probability(reflectance, hero, collapsed)
    r = 0.0
    t = 0.0
    for k in range(reflectance.shape[0]):
        if collapsed and k != hero:
            continue
        r += reflectance[k]
        t += transmittance(row, spectral, reflectance, k, tir)
    if not r + t > 0.0:
        return 0.0
    return min(max(r / (r + t), 0.0), 1.0)


@kernel
def _finite_or_zero(weight):
    for k in range(weight.shape[0]):
        if not math.isfinite(weight[k]):
            weight[k] = 0.0


@kernel
def _sample_smooth(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, weight):
    interface_reflectance(row, spectral, eta, wo[2], wavelength_nm, weight)
    wt, etap, tir = refract(wo, (0.0, 0.0, 1.0), eta)
    if tir and int(row[C_FRESNEL]) != REFRACTION_ONLY:
        for k in range(weight.shape[0]):
            weight[k] = 1.0  # total internal reflection (untinted, as the tint describes F0)
        return (-wo[0], -wo[1], wo[2]), math.inf, SAMPLED_DELTA, 1.0
    p = reflect_probability(row, spectral, weight, hero, collapsed, tir)
    if u0 < p:
        for k in range(weight.shape[0]):
            weight[k] = weight[k] / p
        _finite_or_zero(weight)
        return (-wo[0], -wo[1], wo[2]), math.inf, SAMPLED_DELTA, 1.0
    if tir:
        weight[:] = 0.0
        return wt, 0.0, SAMPLED_DELTA | SAMPLED_TRANSMISSION, 1.0
    scale = 1.0 / ((1.0 - p) * etap * etap)
    for k in range(weight.shape[0]):
        weight[k] = transmittance(row, spectral, weight, k, False) * scale
    _finite_or_zero(weight)
    return wt, math.inf, SAMPLED_DELTA | SAMPLED_TRANSMISSION, etap * etap


@kernel
def _sample_rough(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    alpha = row[C_ALPHA]
    wm = sample_visible_normal(wo, alpha, u1, u2)
    cos_om = wo[0] * wm[0] + wo[1] * wm[1] + wo[2] * wm[2]
    interface_reflectance(row, spectral, eta, cos_om, wavelength_nm, weight)
    wt, etap, tir = refract(wo, wm, eta)
    p = 1.0 if tir and int(row[C_FRESNEL]) != REFRACTION_ONLY else reflect_probability(
        row, spectral, weight, hero, collapsed, tir)
    pdf_wm = visible_normal_pdf(wo, wm, alpha)
    if u0 < p:
        wi = reflect(wo, wm)
        valid = wo[2] * wi[2] > 0.0
        pdf = pdf_wm / (4.0 * abs(cos_om)) * p
        scale = 1.0 / p
        flags = 0
        etap = 1.0
        if tir:
            weight[:] = 1.0
    else:
        wi = wt
        valid = (not tir) and wo[2] * wi[2] < 0.0
        cos_im = wi[0] * wm[0] + wi[1] * wm[1] + wi[2] * wm[2]
        denom = cos_im + cos_om / etap
        pdf = pdf_wm * abs(cos_im) / (denom * denom) * (1.0 - p)
        scale = 1.0 / ((1.0 - p) * etap * etap)
        flags = SAMPLED_TRANSMISSION
    ratio = ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha)
    for k in range(weight.shape[0]):
        fraction = weight[k] if flags == 0 else transmittance(row, spectral, weight, k, tir)
        weight[k] = ratio * fraction * scale
        valid = valid and math.isfinite(weight[k])
    if not (valid and math.isfinite(pdf) and pdf > 0.0):
        weight[:] = 0.0
        return wi, 0.0, flags, 1.0
    return wi, pdf, flags, etap * etap


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale = eta'² on refraction); ``weight[k]`` = f |cos wi| / pdf."""
    if row[C_ALPHA] < SMOOTH_ALPHA:
        return _sample_smooth(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, weight)
    return _sample_rough(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` (without the cosine); returns the pdf of ``sample`` for ``wi`` (0 when smooth)."""
    alpha = row[C_ALPHA]
    f[:] = 0.0
    cos_o, cos_i = wo[2], wi[2]
    if alpha < SMOOTH_ALPHA or cos_o == 0.0 or cos_i == 0.0:
        return 0.0
    is_reflection = cos_o * cos_i > 0.0
    etap = 1.0 if is_reflection else (eta if cos_o > 0.0 else 1.0 / eta)
    hx, hy, hz = wi[0] * etap + wo[0], wi[1] * etap + wo[1], wi[2] * etap + wo[2]
    n = math.sqrt(hx * hx + hy * hy + hz * hz)
    if n <= 0.0:
        return 0.0
    sign = -1.0 if hz < 0.0 else 1.0
    wm = (sign * hx / n, sign * hy / n, sign * hz / n)
    cos_om = wo[0] * wm[0] + wo[1] * wm[1] + wo[2] * wm[2]
    cos_im = wi[0] * wm[0] + wi[1] * wm[1] + wi[2] * wm[2]
    if not (cos_im * cos_i > 0.0 and cos_om * cos_o > 0.0):
        return 0.0
    interface_reflectance(row, spectral, eta, cos_om, wavelength_nm, f)
    _, _, tir = refract(wo, wm, eta)
    p = 1.0 if tir and int(row[C_FRESNEL]) != REFRACTION_ONLY else reflect_probability(
        row, spectral, f, hero, collapsed, tir)
    d = ggx_d(wm, alpha)
    g = ggx_g2(wo, wi, alpha)
    pdf_wm = visible_normal_pdf(wo, wm, alpha)
    denom = (cos_im + cos_om / etap) ** 2
    if is_reflection:
        scalar = d * g / (4.0 * abs(cos_i * cos_o))
        pdf = pdf_wm / (4.0 * abs(cos_om)) * p
    else:
        scalar = d * g * abs(cos_im * cos_om) / (abs(cos_i * cos_o) * denom) / (etap * etap)
        pdf = pdf_wm * abs(cos_im) / denom * (1.0 - p)
    ok = math.isfinite(pdf)
    for k in range(f.shape[0]):
        if is_reflection:
            fraction = 1.0 if tir else f[k]
        else:
            fraction = transmittance(row, spectral, f, k, tir)
        f[k] = scalar * fraction
        ok = ok and math.isfinite(f[k])
    if not ok:
        f[:] = 0.0
        return 0.0
    return pdf
