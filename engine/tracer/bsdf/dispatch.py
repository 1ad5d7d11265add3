"""One entry point per BSDF operation: a closure's kind picks its model; a material's closures combine.

A material is a sum of closures, f = Σ t_i f_i with t_i(λ) the closure's tint (``spectral[i, 2]``).
Sampling picks closure i with probability w_i / Σ w (``C_WEIGHT``: an estimate of the closure's share of
the reflected light) and samples it; for a non-delta pick the weight and pdf are those of the whole
sum (the other non-delta closures are evaluated: one-sample MIS over closures), for a delta pick the
closure's own weight × t_i × Σ w / w_i. With one closure this is that closure times its tint.
"""

from __future__ import annotations

import math

from ..jit import kernel
from . import conductor, dielectric, diffuse, hair, sheen, subsurface_entry, thin_film, translucent, transparent
from .closure_frame import (bump_shadowing, has_own_frame, into_closure_frame, out_of_closure_frame,
                            terminator_softening)
from .closure import (C_ALPHA, C_KIND, C_MIRROR, C_WEIGHT, CONDUCTOR, DIELECTRIC, DIFFUSE, HAIR, SAMPLED_DELTA,
                      SAMPLED_DIFFUSE, SAMPLED_NULL, SAMPLED_TRANSMISSION, SHEEN, SMOOTH_ALPHA, SUBSURFACE, THIN_FILM,
                      TRANSLUCENT, TRANSPARENT)


@kernel
def closure_is_delta(row):
    kind = int(row[C_KIND])
    if kind == THIN_FILM or kind == TRANSPARENT or kind == SUBSURFACE:  # a subsurface entry has no pdf either
        return True
    if kind == CONDUCTOR or kind == DIELECTRIC:
        return row[C_ALPHA] < SMOOTH_ALPHA
    return False


@kernel
def closure_sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    framed = has_own_frame(row)
    if framed:
        wo = into_closure_frame(row, wo)
    mirror = row[C_MIRROR] > 0.0
    if mirror:
        wo = (wo[0], wo[1], -wo[2])
    kind = int(row[C_KIND])
    if kind == DIFFUSE:
        wi, pdf, flags, eta_scale = diffuse.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                   collapsed, u0, u1, u2, weight)
    elif kind == CONDUCTOR:
        wi, pdf, flags, eta_scale = conductor.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                     collapsed, u0, u1, u2, weight)
    elif kind == DIELECTRIC:
        wi, pdf, flags, eta_scale = dielectric.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                      collapsed, u0, u1, u2, weight)
    elif kind == TRANSLUCENT:
        wi, pdf, flags, eta_scale = translucent.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                       collapsed, u0, u1, u2, weight)
    elif kind == SHEEN:
        wi, pdf, flags, eta_scale = sheen.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                 collapsed, u0, u1, u2, weight)
    elif kind == HAIR:
        wi, pdf, flags, eta_scale = hair.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                collapsed, u0, u1, u2, weight)
    elif kind == TRANSPARENT:
        wi, pdf, flags, eta_scale = transparent.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                       collapsed, u0, u1, u2, weight)
    elif kind == SUBSURFACE:  # into the surface: Cycles tests no bump shadowing there
        wi, pdf, flags, eta_scale = subsurface_entry.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                            collapsed, u0, u1, u2, weight)
        if framed:
            wi = out_of_closure_frame(row, wi)
        return wi, pdf, flags, eta_scale
    else:
        wi, pdf, flags, eta_scale = thin_film.sample(row, spectral, eta, wo, wavelength_nm, hero,
                                                     collapsed, u0, u1, u2, weight)
    if mirror:
        wi = (wi[0], wi[1], -wi[2])
    if framed:
        wi = out_of_closure_frame(row, wi)
    shadowing = bump_shadowing(row, wi, False)
    if not flags & (SAMPLED_TRANSMISSION | SAMPLED_NULL):  # Cycles softens reflections only when sampling
        shadowing *= terminator_softening(row, wi, False)
    if shadowing != 1.0:
        for k in range(weight.shape[0]):
            weight[k] *= shadowing
    return wi, pdf, flags, eta_scale


@kernel
def _evaluate_lobe(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    if row[C_MIRROR] > 0.0:
        wo = (wo[0], wo[1], -wo[2])
        wi = (wi[0], wi[1], -wi[2])
    kind = int(row[C_KIND])
    if kind == DIFFUSE:
        return diffuse.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == CONDUCTOR:
        return conductor.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == DIELECTRIC:
        return dielectric.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == TRANSLUCENT:
        return translucent.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == SHEEN:
        return sheen.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == HAIR:
        return hair.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == TRANSPARENT:
        return transparent.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    if kind == SUBSURFACE:
        return subsurface_entry.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
    return thin_film.evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)


@kernel
def closure_evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` of one closure (without its tint) for directions in the material's frame; returns its pdf.
    A closure with a frame of its own gets its cosine there, as Cycles evaluates each closure about its own
    normal: f is scaled by |cos_closure| / |cos_material| so that the callers' |cos_material| gives it; and
    Cycles' bump shadowing term (``closure_frame.bump_shadowing``) where a bump turned its normal, and its shadow
    terminator Shading Offset (``closure_frame.terminator_softening``)."""
    if has_own_frame(row):
        wo_c = into_closure_frame(row, wo)
        wi_c = into_closure_frame(row, wi)
        pdf = _evaluate_lobe(row, spectral, eta, wo_c, wi_c, wavelength_nm, hero, collapsed, f)
        scale = abs(wi_c[2]) / abs(wi[2]) if wi[2] != 0.0 else 0.0
    else:
        pdf = _evaluate_lobe(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f)
        scale = 1.0
    scale *= bump_shadowing(row, wi, True) * terminator_softening(row, wi, True)
    if scale != 1.0:
        for k in range(f.shape[0]):
            f[k] *= scale
    return pdf


@kernel
def _tinted(spectral, c, values):
    tint = spectral[c, 2]
    for k in range(values.shape[0]):
        values[k] *= tint[k]


@kernel
def bsdf_sample(rows, spectral, eta, count, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight, scratch):
    """Sample the material of ``count`` resolved closures: (wi, pdf, sampled flags, eta scale, the closure
    sampled) and ``weight[k]`` = f |cos wi| / pdf. ``scratch`` is float64 [2, K]."""
    if count == 1:
        wi, pdf, flags, eta_scale = closure_sample(rows[0], spectral[0], eta[0], wo, wavelength_nm, hero, collapsed,
                                                   u0, u1, u2, weight)
        _tinted(spectral, 0, weight)
        if int(rows[0, C_KIND]) == DIFFUSE:
            flags |= SAMPLED_DIFFUSE
        return wi, pdf, flags, eta_scale, 0
    total = 0.0
    for c in range(count):
        total += rows[c, C_WEIGHT]
    if not total > 0.0:
        weight[:] = 0.0
        return (0.0, 0.0, 1.0), 0.0, 0, 1.0, 0
    target = u0 * total
    chosen = -1
    before = 0.0
    start = 0.0
    for c in range(count):
        w = rows[c, C_WEIGHT]
        if w > 0.0:
            chosen = c
            start = before
            if target < before + w:
                break
            before += w
    if chosen < 0:
        weight[:] = 0.0
        return (0.0, 0.0, 1.0), 0.0, 0, 1.0, 0
    before = start
    w_chosen = rows[chosen, C_WEIGHT]
    u_lobe = min(max((target - before) / w_chosen, 0.0), 0.9999999999999999)
    wi, pdf, flags, eta_scale = closure_sample(rows[chosen], spectral[chosen], eta[chosen], wo, wavelength_nm, hero,
                                               collapsed, u_lobe, u1, u2, weight)
    if int(rows[chosen, C_KIND]) == DIFFUSE:
        flags |= SAMPLED_DIFFUSE
    if flags & SAMPLED_DELTA or pdf <= 0.0:
        _tinted(spectral, chosen, weight)
        for k in range(weight.shape[0]):
            weight[k] *= total / w_chosen
        return wi, pdf, flags, eta_scale, chosen
    cos = abs(wi[2])
    total_f = scratch[1]
    tint = spectral[chosen, 2]
    for k in range(weight.shape[0]):
        total_f[k] = tint[k] * weight[k] * pdf / cos if cos > 0.0 else 0.0
    mixture_pdf = w_chosen / total * pdf
    for c in range(count):
        if c == chosen or closure_is_delta(rows[c]):
            continue
        pdf_c = closure_evaluate(rows[c], spectral[c], eta[c], wo, wi, wavelength_nm, hero, collapsed, scratch[0])
        mixture_pdf += rows[c, C_WEIGHT] / total * pdf_c
        tint = spectral[c, 2]
        for k in range(weight.shape[0]):
            total_f[k] += tint[k] * scratch[0, k]
    for k in range(weight.shape[0]):
        weight[k] = total_f[k] * cos / mixture_pdf if mixture_pdf > 0.0 else 0.0
    return wi, mixture_pdf, flags, eta_scale, chosen


@kernel
def bsdf_evaluate(rows, spectral, eta, count, wo, wi, wavelength_nm, hero, collapsed, f, scratch):
    """``f[k]`` of the material (without the cosine); returns the pdf of ``bsdf_sample`` for ``wi``."""
    if count == 1:
        pdf = closure_evaluate(rows[0], spectral[0], eta[0], wo, wi, wavelength_nm, hero, collapsed, f)
        _tinted(spectral, 0, f)
        return pdf
    total = 0.0
    for c in range(count):
        total += rows[c, C_WEIGHT]
    f[:] = 0.0
    pdf = 0.0
    for c in range(count):
        pdf_c = closure_evaluate(rows[c], spectral[c], eta[c], wo, wi, wavelength_nm, hero, collapsed, scratch[0])
        if total > 0.0:
            pdf += rows[c, C_WEIGHT] / total * pdf_c
        tint = spectral[c, 2]
        for k in range(f.shape[0]):
            f[k] += tint[k] * scratch[0, k]
    return pdf if math.isfinite(pdf) else 0.0
