"""``HAIR`` closures in the material's shading frame: a fibre's frame from its tangent and the view, and the
Chiang model (``hair_chiang``) sampled and evaluated there, or the Hair BSDF's lobes (``hair_kajiya``,
``C_HAIR_MODEL``) about the same tangent.

The closure row carries, set per hit (``materials.hair_setup``, ``materials.closure_normals.orient_closures``),
the curve tangent in the material's frame (``C_HAIR_TX/TY/TZ``), where the view met the fibre (``C_HAIR_H``)
and Cycles' lobe parameters (``C_HAIR_V``, ``C_HAIR_S``, ``C_HAIR_M0``); ``spectral[0]`` holds the absorption
coefficient per wavelength. As in Cycles (``bsdf_hair_chiang_setup``): X = the tangent, Y = X × view
(normalised), Z = X × Y.

A fibre scatters all round: F = f |cos| is what Cycles' model gives, so ``f`` here is F over the cosine of the
material's normal that the callers multiply back. A sampled direction is labelled a transmission where it
leaves on the other side of the shading normal than the view (the side the path's next ray takes; Cycles labels
every lobe but R a transmission and does not check sides for hair), so that the geometric-side test of
``stages.shade`` holds.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..vec3 import cross, dot, tangents
from .closure import (C_HAIR_H, C_HAIR_IOR, C_HAIR_M0, C_HAIR_MODEL, C_HAIR_OFFSET, C_HAIR_RADIAL, C_HAIR_ROUGHNESS,
                      C_HAIR_S, C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ, C_HAIR_V, SAMPLED_TRANSMISSION)
from .hair_chiang import chiang_sample, chiang_value, clamp_roughness
from .hair_kajiya import kajiya_pdf, kajiya_sample


@kernel
def fibre_frame(row, wo):
    """(X, Y, Z): the fibre's frame for the view ``wo`` (material frame)."""
    x = (row[C_HAIR_TX], row[C_HAIR_TY], row[C_HAIR_TZ])
    y = cross(x, wo)
    size = math.sqrt(dot(y, y))
    if size > 1e-12:
        y = (y[0] / size, y[1] / size, y[2] / size)
    else:  # looking along the fibre: any Y across it
        y = tangents(x)[0]
    return x, y, cross(x, y)


@kernel
def _angles(w, x, y, z):
    """(sin θ, φ) of ``w`` in the fibre's frame."""
    return min(max(dot(w, x), -1.0), 1.0), math.atan2(dot(w, z), dot(w, y))


@kernel
def _per_cosine(wi, values):
    c = abs(wi[2])
    scale = 1.0 / c if c > 0.0 else 0.0
    for k in range(values.shape[0]):
        values[k] *= scale


@kernel
def _cuticle(row):
    """Cycles' α: the node's Offset (radians) negated (``bsdf_hair_chiang_setup``)."""
    return -row[C_HAIR_OFFSET]


@kernel
def _kajiya(row):
    """(component, unit tangent, RoughnessU, RoughnessV clamped as Cycles, Cycles' offset: the input negated)."""
    return (int(row[C_HAIR_MODEL]), (row[C_HAIR_TX], row[C_HAIR_TY], row[C_HAIR_TZ]),
            clamp_roughness(row[C_HAIR_ROUGHNESS]), clamp_roughness(row[C_HAIR_RADIAL]), -row[C_HAIR_OFFSET])


@kernel
def evaluate(row, spectral, eta, wo, wi, wavelength_nm, hero, collapsed, f):
    """``f[k]`` (F / |cos wi| of the material's normal); returns the pdf of ``sample``."""
    if int(row[C_HAIR_MODEL]) != 0:
        component, tangent, r1, r2, offset = _kajiya(row)
        pdf = kajiya_pdf(component, tangent, r1, r2, offset, wo, wi)
        for k in range(f.shape[0]):
            f[k] = pdf
        _per_cosine(wi, f)
        return pdf
    x, y, z = fibre_frame(row, wo)
    sin_o, phi_o = _angles(wo, x, y, z)
    sin_i, phi_i = _angles(wi, x, y, z)
    pdf = chiang_value(sin_i, phi_i - phi_o, sin_o, row[C_HAIR_H], row[C_HAIR_IOR], _cuticle(row), row[C_HAIR_V],
                       row[C_HAIR_S], row[C_HAIR_M0], spectral[0], hero, collapsed, f)
    _per_cosine(wi, f)
    return pdf


@kernel
def sample(row, spectral, eta, wo, wavelength_nm, hero, collapsed, u0, u1, u2, weight):
    """(wi, pdf, sampled flags, eta scale); ``weight[k]`` = F / pdf."""
    if int(row[C_HAIR_MODEL]) != 0:
        component, tangent, r1, r2, offset = _kajiya(row)
        wi, pdf = kajiya_sample(component, tangent, r1, r2, offset, wo, u1, u2)
        value = 1.0 if pdf > 0.0 and math.isfinite(pdf) else 0.0
        for k in range(weight.shape[0]):
            weight[k] = value
        return wi, pdf * value, SAMPLED_TRANSMISSION if wi[2] * wo[2] < 0.0 else 0, 1.0
    x, y, z = fibre_frame(row, wo)
    sin_o, phi_o = _angles(wo, x, y, z)
    h, ior, alpha = row[C_HAIR_H], row[C_HAIR_IOR], _cuticle(row)
    v, s, m0 = row[C_HAIR_V], row[C_HAIR_S], row[C_HAIR_M0]
    sin_i, phi, _ = chiang_sample(sin_o, h, ior, alpha, v, s, m0, spectral[0], hero, collapsed, u0, u1, u2)
    cos_i = math.sqrt(max(0.0, 1.0 - sin_i * sin_i))
    phi_i = phi_o + phi
    cp, sp = cos_i * math.cos(phi_i), cos_i * math.sin(phi_i)
    wi = (sin_i * x[0] + cp * y[0] + sp * z[0], sin_i * x[1] + cp * y[1] + sp * z[1],
          sin_i * x[2] + cp * y[2] + sp * z[2])
    pdf = chiang_value(sin_i, phi, sin_o, h, ior, alpha, v, s, m0, spectral[0], hero, collapsed, weight)
    if not (pdf > 0.0 and math.isfinite(pdf)):
        weight[:] = 0.0
        return wi, 0.0, 0, 1.0
    for k in range(weight.shape[0]):
        weight[k] /= pdf
    flags = SAMPLED_TRANSMISSION if wi[2] * wo[2] < 0.0 else 0
    return wi, pdf, flags, 1.0
