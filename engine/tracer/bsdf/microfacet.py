"""Isotropic GGX (Trowbridge-Reitz) microfacet distribution in a local frame (+Z = normal).

Visible-normal sampling follows Heitz, "Sampling the GGX Distribution of Visible
Normals", JCGT 7(4), 2018; masking-shadowing is Smith's height-correlated form
G2 = 1 / (1 + Lambda(wo) + Lambda(wi)). ``alpha`` is Blender's roughness squared.
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot, norm


def ggx_d(wm: np.ndarray, alpha: np.ndarray | float) -> np.ndarray:
    """Normal distribution D(wm) [n] (per steradian of microfacet normal)."""
    cos2 = wm[:, 2] ** 2
    a2 = np.asarray(alpha, dtype=np.float64) ** 2
    denom = cos2 * (a2 - 1.0) + 1.0
    return np.where(wm[:, 2] > 0, a2 / (np.pi * denom * denom), 0.0)


def ggx_lambda(w: np.ndarray, alpha) -> np.ndarray:
    """Smith's Lambda(w) [n]."""
    cos2 = w[:, 2] ** 2
    sin2 = np.maximum(0.0, 1.0 - cos2)
    with np.errstate(divide="ignore", invalid="ignore"):
        tan2 = sin2 / cos2
    tan2 = np.where(cos2 > 0, tan2, np.inf)
    a2 = np.asarray(alpha, dtype=np.float64) ** 2
    return 0.5 * (np.sqrt(1.0 + a2 * tan2) - 1.0)


def ggx_g1(w, alpha) -> np.ndarray:
    """Smith masking G1(w) [n]."""
    return 1.0 / (1.0 + ggx_lambda(w, alpha))


def ggx_g2(wo, wi, alpha) -> np.ndarray:
    """Height-correlated masking-shadowing G2(wo, wi) [n]."""
    return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha))


def visible_normal_pdf(w, wm, alpha) -> np.ndarray:
    """Density of visible normals D_w(wm) = G1(w) max(0, w.wm) D(wm) / |cos w| [n]
    (``w`` may be below the surface: it is mirrored up, as in sampling)."""
    w_up = w * np.where(w[:, 2] < 0, -1.0, 1.0)[:, None]
    cos_m = np.maximum(dot(w_up, wm), 0.0)
    cos = np.abs(w[:, 2])
    with np.errstate(divide="ignore", invalid="ignore"):
        pdf = ggx_g1(w_up, alpha) * cos_m * ggx_d(wm, alpha) / cos
    return np.where(cos > 0, pdf, 0.0)


def sample_visible_normal(w: np.ndarray, alpha, u: np.ndarray) -> np.ndarray:
    """Microfacet normals [n,3] distributed by D_w (Heitz 2018); ``u`` [n,2] uniform.

    ``w`` below the surface is mirrored to the upper hemisphere first."""
    alpha = np.broadcast_to(np.asarray(alpha, dtype=np.float64), (len(w),))
    w_up = w * np.where(w[:, 2] < 0, -1.0, 1.0)[:, None]
    vh = np.column_stack([alpha * w_up[:, 0], alpha * w_up[:, 1], w_up[:, 2]])
    vh /= norm(vh)[:, None]
    lensq = vh[:, 0] ** 2 + vh[:, 1] ** 2
    inv = np.where(lensq > 0, 1.0 / np.sqrt(np.where(lensq > 0, lensq, 1.0)), 0.0)
    t1 = np.where(
        (lensq > 0)[:, None], np.column_stack([-vh[:, 1] * inv, vh[:, 0] * inv, np.zeros(len(w))]), [1.0, 0.0, 0.0]
    )
    t2 = np.cross(vh, t1)
    r = np.sqrt(u[:, 0])
    phi = 2.0 * np.pi * u[:, 1]
    p1 = r * np.cos(phi)
    p2 = r * np.sin(phi)
    s = 0.5 * (1.0 + vh[:, 2])
    p2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + s * p2
    p3 = np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))
    nh = p1[:, None] * t1 + p2[:, None] * t2 + p3[:, None] * vh
    ne = np.column_stack([alpha * nh[:, 0], alpha * nh[:, 1], np.maximum(1e-12, nh[:, 2])])
    return ne / norm(ne)[:, None]


def reflect(w: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Mirror ``w`` (pointing away from the surface) about ``n``: 2 (w.n) n - w."""
    return 2.0 * dot(w, n)[:, None] * n - w
