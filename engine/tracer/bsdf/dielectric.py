"""Dielectric interfaces (glass): smooth (delta) or rough GGX, optionally under a thin-film coating.

The local +Z is the outward normal: wo.z > 0 arrives from outside (index 1), wo.z < 0 from inside.
``eta`` is the glass index: at the path's hero wavelength when the glass disperses (the path then
carries only its hero), else the constant index. Refracted radiance is scaled by 1/eta'² (radiance is
not symmetric under refraction, Veach 1997 §5.2). Reflection or refraction is chosen with probability
p = mean reflectance over the carried wavelengths (the hero's once collapsed), each column weighted
R_k / p or (1 - R_k) / (1 - p). Rough transmission follows Walter et al. 2007 with visible-normal
sampling (Heitz 2018).
"""

from __future__ import annotations

import math

from ..jit import kernel
from .closure import C_ALPHA, C_COAT_IOR, C_COAT_NM, SAMPLED_DELTA, SAMPLED_TRANSMISSION, SMOOTH_ALPHA
from .microfacet import ggx_d, ggx_g1, ggx_g2, reflect, sample_visible_normal, visible_normal_pdf
from .optics import fresnel_dielectric, refract, thin_film_reflectance


@kernel
def interface_reflectance(row, eta, cos_i, wavelength_nm, out):
    """``out[k]`` = reflectance for signed ``cos_i`` (< 0: from inside) at every carried wavelength."""
    if row[C_COAT_NM] <= 0.0:
        r = fresnel_dielectric(cos_i, eta)
        for k in range(out.shape[0]):
            out[k] = r
        return
    n_in, n_out = (1.0, eta) if cos_i >= 0.0 else (eta, 1.0)
    for k in range(out.shape[0]):
        out[k] = thin_film_reflectance(cos_i, wavelength_nm[k], row[C_COAT_NM], n_in, row[C_COAT_IOR],
                                       complex(n_out, 0.0))


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
def _finite_or_zero(weight):
    for k in range(weight.shape[0]):
        if not math.isfinite(weight[k]):
            weight[k] = 0.0


@kernel
def _sample_smooth(row, eta, wo, wavelength_nm, hero, collapsed, u0, weight):
    interface_reflectance(row, eta, wo[2], wavelength_nm, weight)
    p = choice_probability(weight, hero, collapsed)
    wt, etap, tir = refract(wo, (0.0, 0.0, 1.0), eta)
    if tir or u0 < p:
        for k in range(weight.shape[0]):
            weight[k] = 1.0 if tir else weight[k] / p
        _finite_or_zero(weight)
        return (-wo[0], -wo[1], wo[2]), math.inf, SAMPLED_DELTA, 1.0
    scale = 1.0 / ((1.0 - p) * etap * etap)
    for k in range(weight.shape[0]):
        weight[k] = (1.0 - weight[k]) * scale
    _finite_or_zero(weight)
    return wt, math.inf, SAMPLED_DELTA | SAMPLED_TRANSMISSION, etap * etap


@kernel
def _sample_rough(row, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    alpha = row[C_ALPHA]
    wm = sample_visible_normal(wo, alpha, u1, u2)
    cos_om = wo[0] * wm[0] + wo[1] * wm[1] + wo[2] * wm[2]
    interface_reflectance(row, eta, cos_om, wavelength_nm, weight)
    p = choice_probability(weight, hero, collapsed)
    pdf_wm = visible_normal_pdf(wo, wm, alpha)
    if u0 < p:
        wi = reflect(wo, wm)
        valid = wo[2] * wi[2] > 0.0
        pdf = pdf_wm / (4.0 * abs(cos_om)) * p
        scale = 1.0 / p
        flags = 0
        etap = 1.0
    else:
        wi, etap, tir = refract(wo, wm, eta)
        valid = (not tir) and wo[2] * wi[2] < 0.0
        cos_im = wi[0] * wm[0] + wi[1] * wm[1] + wi[2] * wm[2]
        denom = cos_im + cos_om / etap
        pdf = pdf_wm * abs(cos_im) / (denom * denom) * (1.0 - p)
        scale = 1.0 / ((1.0 - p) * etap * etap)
        flags = SAMPLED_TRANSMISSION
    ratio = ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha)
    for k in range(weight.shape[0]):
        weight[k] = ratio * (weight[k] if flags == 0 else 1.0 - weight[k]) * scale
        valid = valid and math.isfinite(weight[k])
    if not (valid and math.isfinite(pdf) and pdf > 0.0):
        weight[:] = 0.0
        return wi, 0.0, flags, 1.0
    return wi, pdf, flags, etap * etap


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale = eta'² on refraction); ``weight[k]`` = f |cos wi| / pdf."""
    if row[C_ALPHA] < SMOOTH_ALPHA:
        return _sample_smooth(row, eta, wo, wavelength_nm, hero, collapsed, u0, weight)
    return _sample_rough(row, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)


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
    interface_reflectance(row, eta, cos_om, wavelength_nm, f)
    p = choice_probability(f, hero, collapsed)
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
        f[k] = scalar * (f[k] if is_reflection else 1.0 - f[k])
        ok = ok and math.isfinite(f[k])
    if not ok:
        f[:] = 0.0
        return 0.0
    return pdf
