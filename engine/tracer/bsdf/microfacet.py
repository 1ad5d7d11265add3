"""Isotropic GGX (Trowbridge-Reitz) microfacets in the local frame (+Z = normal), per path.

Visible-normal sampling follows Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4),
2018; masking-shadowing is Smith's height-correlated G2 = 1 / (1 + Λ(wo) + Λ(wi)). ``alpha`` is
Blender's roughness squared.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..warps import sincos_turn


@kernel
def ggx_d(wm, alpha):
    """Normal distribution D(wm) (per steradian of microfacet normal)."""
    if wm[2] <= 0.0:
        return 0.0
    a2 = alpha * alpha
    denom = wm[2] * wm[2] * (a2 - 1.0) + 1.0
    return a2 / (math.pi * denom * denom)


@kernel
def ggx_lambda(w, alpha):
    cos2 = w[2] * w[2]
    if cos2 <= 0.0:
        return math.inf
    tan2 = max(0.0, 1.0 - cos2) / cos2
    return 0.5 * (math.sqrt(1.0 + alpha * alpha * tan2) - 1.0)


@kernel
def ggx_g1(w, alpha):
    return 1.0 / (1.0 + ggx_lambda(w, alpha))


@kernel
def ggx_g2(wo, wi, alpha):
    return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha))


@kernel
def ggx_g1_g2(wo, wi, alpha):
    """(G1(wo), G2(wo, wi)), sharing Λ(wo)."""
    lambda_o = ggx_lambda(wo, alpha)
    return 1.0 / (1.0 + lambda_o), 1.0 / (1.0 + lambda_o + ggx_lambda(wi, alpha))


@kernel
def _upper(w):
    return (w[0], w[1], w[2]) if w[2] >= 0.0 else (-w[0], -w[1], -w[2])


@kernel
def visible_normal_pdf(w, wm, alpha):
    """D_w(wm) = G1(w) max(0, w.wm) D(wm) / |cos w| (``w`` below the surface is mirrored up)."""
    cos = abs(w[2])
    if cos <= 0.0:
        return 0.0
    up = _upper(w)
    cos_m = max(up[0] * wm[0] + up[1] * wm[1] + up[2] * wm[2], 0.0)
    return ggx_g1(up, alpha) * cos_m * ggx_d(wm, alpha) / cos


@kernel
def sample_visible_normal(w, alpha, u1, u2):
    """A microfacet normal distributed by D_w (``w`` below the surface is mirrored up first)."""
    up = _upper(w)
    vx, vy, vz = alpha * up[0], alpha * up[1], up[2]
    n = math.sqrt(vx * vx + vy * vy + vz * vz)
    vx, vy, vz = vx / n, vy / n, vz / n
    lensq = vx * vx + vy * vy
    if lensq > 0.0:
        inv = 1.0 / math.sqrt(lensq)
        t1 = (-vy * inv, vx * inv, 0.0)
    else:
        t1 = (1.0, 0.0, 0.0)
    t2 = (vy * t1[2] - vz * t1[1], vz * t1[0] - vx * t1[2], vx * t1[1] - vy * t1[0])
    r = math.sqrt(u1)
    sin_phi, cos_phi = sincos_turn(u2)
    p1 = r * cos_phi
    p2 = r * sin_phi
    s = 0.5 * (1.0 + vz)
    p2 = (1.0 - s) * math.sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2
    p3 = math.sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2))
    hx = p1 * t1[0] + p2 * t2[0] + p3 * vx
    hy = p1 * t1[1] + p2 * t2[1] + p3 * vy
    hz = p1 * t1[2] + p2 * t2[2] + p3 * vz
    ex, ey, ez = alpha * hx, alpha * hy, max(1e-12, hz)
    n = math.sqrt(ex * ex + ey * ey + ez * ez)
    return (ex / n, ey / n, ez / n)


@kernel
def reflect(w, n):
    """Mirror ``w`` (pointing away from the surface) about ``n``: 2 (w.n) n - w."""
    d = 2.0 * (w[0] * n[0] + w[1] * n[1] + w[2] * n[2])
    return (d * n[0] - w[0], d * n[1] - w[1], d * n[2] - w[2])
