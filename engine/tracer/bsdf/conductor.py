"""Conductors (metals): perfect mirror below ``SMOOTH_ALPHA``, else GGX with visible-normal sampling.

Reflectance per wavelength (``C_FRESNEL``): measured n + ik (``spectral[0]``, ``spectral[1]``); Schlick's
form of a normal-incidence reflectance ``spectral[0]`` (a base colour); F82-tint (Principled metallic);
a dielectric's Fresnel at ``C_ETA`` (Principled specular and coat); or none (Glossy BSDF: F = 1). The
measured, Schlick and dielectric forms can sit under a thin-film coating (the base colour then becomes
the real index with that normal reflectance). Rough:
f = D G2 F / (4 cos_o cos_i), sampled by D_wo with weight F G2 / G1(wo).
"""

from __future__ import annotations

import math

from ..jit import inlined, kernel
from .closure import (C_ALPHA, C_COAT_IOR, C_COAT_NM, C_ETA, C_FRESNEL, FRESNEL_CONDUCTOR, FRESNEL_DIELECTRIC,
                      FRESNEL_F82, FRESNEL_NONE, SAMPLED_DELTA, SMOOTH_ALPHA)
from .microfacet import ggx_d, ggx_g1_g2, reflect, sample_visible_normal
from .optics import dielectric_f0, fresnel_conductor, fresnel_dielectric, thin_film_reflectance, tinted_fresnel

# F82-tint (Kutz et al., "Novel aspects of the Adobe Standard Material"): the Schlick curve less
# b cos (1 - cos)^6, b fixed so that F(cos = 1/7, about 82°) is Schlick times the tint.
C82_5 = (6.0 / 7.0) ** 5
C82_WEIGHT = (1.0 / 7.0) * (6.0 / 7.0) ** 6


@inlined
def reflectance(row, spectral, cos_i, wavelength_nm, k):
    """Reflectance of the interface at wavelength column ``k`` for incidence cosine ``cos_i``."""
    cos_i = min(abs(cos_i), 1.0)
    mode = int(row[C_FRESNEL])
    if mode == FRESNEL_NONE:
        return 1.0
    coated = row[C_COAT_NM] > 0.0
    if mode == FRESNEL_CONDUCTOR:
        if coated:
            return thin_film_reflectance(cos_i, wavelength_nm[k], row[C_COAT_NM], 1.0, row[C_COAT_IOR],
                                         complex(spectral[0, k], spectral[1, k]))
        return fresnel_conductor(cos_i, spectral[0, k], spectral[1, k])
    if mode == FRESNEL_DIELECTRIC:
        eta = row[C_ETA]
        if coated:
            f = thin_film_reflectance(cos_i, wavelength_nm[k], row[C_COAT_NM], 1.0, row[C_COAT_IOR],
                                      complex(eta, 0.0))
        else:
            f = fresnel_dielectric(cos_i, eta)
        return tinted_fresnel(f, dielectric_f0(eta), spectral[0, k], coated)
    f0 = spectral[0, k]
    c = 1.0 - cos_i
    c5 = c * c * c * c * c
    if mode == FRESNEL_F82:
        schlick = f0 + (1.0 - f0) * c5
        b = (f0 + (1.0 - f0) * C82_5) * (1.0 - spectral[1, k]) / C82_WEIGHT
        return min(max(schlick - b * cos_i * c5 * c, 0.0), 1.0)
    if coated:
        r = math.sqrt(min(max(f0, 0.0), 0.999))
        return thin_film_reflectance(cos_i, wavelength_nm[k], row[C_COAT_NM], 1.0, row[C_COAT_IOR],
                                     complex((1.0 + r) / (1.0 - r), 0.0))
    return f0 + (1.0 - f0) * c5


@inlined
def _shared_fresnel(row, cos_i):
    """(F, F0) of an uncoated dielectric reflection, the same at every wavelength but for its tint, so
    computed once per call; (-1, 0) for the other reflectance models."""
    if int(row[C_FRESNEL]) != FRESNEL_DIELECTRIC or row[C_COAT_NM] > 0.0:
        return -1.0, 0.0
    return fresnel_dielectric(min(abs(cos_i), 1.0), row[C_ETA]), dielectric_f0(row[C_ETA])


@inlined
def _reflectance_at(row, spectral, cos_i, wavelength_nm, k, shared):
    f, f0 = shared
    if f >= 0.0:
        return tinted_fresnel(f, f0, spectral[0, k], False)
    return reflectance(row, spectral, cos_i, wavelength_nm, k)


@kernel
def reflectances(row, spectral, cos_i, wavelength_nm, scale, out):
    """``out[k]`` = ``scale`` × the reflectance at every carried wavelength, in one call (calls that take
    arrays are not free in numba, and a dielectric's Fresnel is computed once, not per wavelength)."""
    shared = _shared_fresnel(row, cos_i)
    for k in range(out.shape[0]):
        out[k] = scale * _reflectance_at(row, spectral, cos_i, wavelength_nm, k, shared)


@kernel
def mean_tinted_reflectance(row, spectral, cos_i, wavelength_nm):
    """Mean over the carried wavelengths of the closure's tint (``spectral[2]``) × its reflectance: its share
    of the reflected light, for choosing among a material's closures."""
    shared = _shared_fresnel(row, cos_i)
    count = wavelength_nm.shape[0]
    total = 0.0
    for k in range(count):
        total += spectral[2, k] * _reflectance_at(row, spectral, cos_i, wavelength_nm, k, shared)
    return total / count


@inlined
def _reflection_pdf(d, g1_o, cos_o):
    """pdf of wi = reflect(wo, wm) with wm drawn from the visible normals, D_wo(wm) / (4 wo.wm); D_wo(wm) =
    G1(wo) (wo.wm) D(wm) / cos_o, so the wo.wm cancel (``cos_o`` > 0, wo.wm > 0)."""
    return g1_o * d / (4.0 * cos_o)


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = f |cos wi| / pdf (F for the mirror)."""
    alpha = row[C_ALPHA]
    if alpha < SMOOTH_ALPHA:
        wi = (-wo[0], -wo[1], wo[2])
        if wo[2] <= 0.0:
            weight[:] = 0.0
            return wi, 0.0, SAMPLED_DELTA, 1.0
        reflectances(row, spectral, wo[2], wavelength_nm, 1.0, weight)
        return wi, math.inf, SAMPLED_DELTA, 1.0
    if wo[2] <= 0.0:
        weight[:] = 0.0
        return (-wo[0], -wo[1], wo[2]), 0.0, 0, 1.0
    wm = sample_visible_normal(wo, alpha, u1, u2)
    wi = reflect(wo, wm)
    cos_om = min(max(wo[0] * wm[0] + wo[1] * wm[1] + wo[2] * wm[2], 0.0), 1.0)
    g1, g2 = ggx_g1_g2(wo, wi, alpha)
    pdf = _reflection_pdf(ggx_d(wm, alpha), g1, wo[2]) if cos_om > 0.0 else 0.0
    ratio = g2 / g1
    if wi[2] <= 0.0 or not (pdf > 0.0 and math.isfinite(pdf)) or not math.isfinite(ratio):
        weight[:] = 0.0
        return wi, 0.0, 0, 1.0
    reflectances(row, spectral, cos_om, wavelength_nm, ratio, weight)
    return wi, pdf, 0, 1.0


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` (without the cosine); returns the pdf of ``sample`` for ``wi`` (0 for the mirror)."""
    alpha = row[C_ALPHA]
    f[:] = 0.0
    if alpha < SMOOTH_ALPHA or wo[2] <= 0.0 or wi[2] <= 0.0:
        return 0.0
    hx, hy, hz = wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]
    n = math.sqrt(hx * hx + hy * hy + hz * hz)
    if n <= 0.0:
        return 0.0
    wm = (hx / n, hy / n, hz / n)
    cos_om = min(max(wo[0] * wm[0] + wo[1] * wm[1] + wo[2] * wm[2], 0.0), 1.0)
    if cos_om <= 0.0:
        return 0.0
    d = ggx_d(wm, alpha)
    g1, g2 = ggx_g1_g2(wo, wi, alpha)
    scalar = d * g2 / (4.0 * wo[2] * wi[2])
    pdf = _reflection_pdf(d, g1, wo[2])
    if not (math.isfinite(scalar) and math.isfinite(pdf)):
        return 0.0
    reflectances(row, spectral, cos_om, wavelength_nm, scalar, f)
    return pdf
