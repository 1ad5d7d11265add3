"""One entry point per BSDF operation: a closure's kind picks its model; a material's closures combine.

A material is a weighted sum of closures, f = Σ w_i f_i. Sampling picks closure i with probability
w_i / Σ w and samples it; for a non-delta pick the weight and pdf are those of the whole sum (the
other non-delta closures are evaluated: one-sample MIS over closures), for a delta pick the closure's
own weight times Σ w. With one closure (every material Prism exports today) this is that closure.
"""

from __future__ import annotations

import math

from ..jit import kernel
from . import conductor, dielectric, diffuse, thin_film
from .closure import (C_ALPHA, C_KIND, C_WEIGHT, CONDUCTOR, DIELECTRIC, DIFFUSE, SAMPLED_DELTA, SAMPLED_DIFFUSE,
                      SMOOTH_ALPHA, THIN_FILM)


@kernel
def closure_is_delta(row):
    kind = int(row[C_KIND])
    if kind == THIN_FILM:
        return True
    if kind == CONDUCTOR or kind == DIELECTRIC:
        return row[C_ALPHA] < SMOOTH_ALPHA
    return False


@kernel
def closure_sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    kind = int(row[C_KIND])
    if kind == DIFFUSE:
        return diffuse.sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)
    if kind == CONDUCTOR:
        return conductor.sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)
    if kind == DIELECTRIC:
        return dielectric.sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)
    return thin_film.sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight)


@kernel
def closure_evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    kind = int(row[C_KIND])
    if kind == DIFFUSE:
        return diffuse.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == CONDUCTOR:
        return conductor.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == DIELECTRIC:
        return dielectric.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    return thin_film.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)


@kernel
def bsdf_sample(rows, spectral, eta, count, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight, scratch):
    """Sample the material of ``count`` resolved closures: (wi, pdf, sampled flags, eta scale) and
    ``weight[k]`` = f |cos wi| / pdf. ``scratch`` is float64 [2, K]."""
    if count == 1:
        wi, pdf, flags, eta_scale = closure_sample(rows[0], spectral[0], eta[0], wo, wavelength_nm, hero, collapsed,
                                                   u0, u1, u2, weight)
        if int(rows[0, C_KIND]) == DIFFUSE:
            flags |= SAMPLED_DIFFUSE
        return wi, pdf, flags, eta_scale
    total = 0.0
    for c in range(count):
        total += rows[c, C_WEIGHT]
    target = u0 * total
    chosen = count - 1
    before = 0.0
    for c in range(count):
        if target < before + rows[c, C_WEIGHT] or c == count - 1:
            chosen = c
            break
        before += rows[c, C_WEIGHT]
    w_chosen = rows[chosen, C_WEIGHT]
    u_lobe = min(max((target - before) / w_chosen, 0.0), 0.9999999999999999) if w_chosen > 0.0 else 0.0
    wi, pdf, flags, eta_scale = closure_sample(rows[chosen], spectral[chosen], eta[chosen], wo, wavelength_nm, hero,
                                               collapsed, u_lobe, u1, u2, weight)
    if int(rows[chosen, C_KIND]) == DIFFUSE:
        flags |= SAMPLED_DIFFUSE
    if flags & SAMPLED_DELTA or pdf <= 0.0:
        for k in range(weight.shape[0]):
            weight[k] *= total
        return wi, pdf, flags, eta_scale
    cos = abs(wi[2])
    total_f = scratch[1]
    for k in range(weight.shape[0]):
        total_f[k] = w_chosen * weight[k] * pdf / cos if cos > 0.0 else 0.0
    mixture_pdf = w_chosen / total * pdf
    for c in range(count):
        if c == chosen or closure_is_delta(rows[c]):
            continue
        pdf_c = closure_evaluate(rows[c], spectral[c], eta[c], wo, wi, wavelength_nm, hero, collapsed, scratch[0])
        mixture_pdf += rows[c, C_WEIGHT] / total * pdf_c
        for k in range(weight.shape[0]):
            total_f[k] += rows[c, C_WEIGHT] * scratch[0, k]
    for k in range(weight.shape[0]):
        weight[k] = total_f[k] * cos / mixture_pdf if mixture_pdf > 0.0 else 0.0
    return wi, mixture_pdf, flags, eta_scale


@kernel
def bsdf_evaluate(rows, spectral, eta, count, wo, wi, wavelength_nm, hero, collapsed, f, scratch):
    """``f[k]`` of the material (without the cosine); returns the pdf of ``bsdf_sample`` for ``wi``."""
    if count == 1:
        return closure_evaluate(rows[0], spectral[0], eta[0], wo, wi, wavelength_nm, hero, collapsed, f)
    total = 0.0
    for c in range(count):
        total += rows[c, C_WEIGHT]
    f[:] = 0.0
    pdf = 0.0
    for c in range(count):
        pdf_c = closure_evaluate(rows[c], spectral[c], eta[c], wo, wi, wavelength_nm, hero, collapsed, scratch[0])
        pdf += rows[c, C_WEIGHT] / total * pdf_c
        for k in range(f.shape[0]):
            f[k] += rows[c, C_WEIGHT] * scratch[0, k]
    return pdf if math.isfinite(pdf) else 0.0
