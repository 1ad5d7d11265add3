"""Conductors: perfect mirror (alpha < 1e-3) or rough GGX with visible-normal sampling.

``fresnel(cos_i [n], lam [n,K]) -> F [n,K]`` is the reflectance of the interface
(measured n, k; Schlick from a base colour; or a thin-film coating over either).
Rough: f = D G2 F / (4 cos_o cos_i); sampled by D_wo, weight F G2 / G1(wo).
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot, norm, where_rows

from .base import BSDF, BSDFSample
from .microfacet import ggx_d, ggx_g1, ggx_g2, reflect, sample_visible_normal, visible_normal_pdf

SMOOTH_ALPHA = 1e-3


class Conductor(BSDF):
    kind = "conductor"

    def __init__(self, alpha: float, fresnel):
        self.alpha = float(alpha)
        self.fresnel = fresnel
        self.delta = self.alpha < SMOOTH_ALPHA

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        n, k = lam.shape
        if self.delta:
            return np.zeros((n, k)), np.zeros(n)
        ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
        wm = wo + wi
        wm /= np.maximum(norm(wm), 1e-300)[:, None]
        cos_om = np.clip(dot(wo, wm), 0.0, 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            scalar = ggx_d(wm, self.alpha) * ggx_g2(wo, wi, self.alpha) / (4.0 * wo[:, 2] * wi[:, 2])
            pdf = visible_normal_pdf(wo, wm, self.alpha) / (4.0 * cos_om)
        scalar = np.where(ok & np.isfinite(scalar), scalar, 0.0)
        pdf = np.where(ok & np.isfinite(pdf), pdf, 0.0)
        return scalar[:, None] * self.fresnel(cos_om, lam), pdf

    def sample(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        if self.delta:
            wi = wo * np.array([-1.0, -1.0, 1.0])
            ok = wo[:, 2] > 0
            weight = where_rows(ok, self.fresnel(np.clip(wo[:, 2], 0, 1), lam), 0.0)
            return BSDFSample(wi, weight, np.where(ok, np.inf, 0.0), np.ones(n, dtype=bool), np.ones(n))
        wm = sample_visible_normal(wo, self.alpha, u[:, 1:3])
        wi = reflect(wo, wm)
        ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
        cos_om = np.clip(dot(wo, wm), 0.0, 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = ggx_g2(wo, wi, self.alpha) / ggx_g1(wo, self.alpha)
            pdf = visible_normal_pdf(wo, wm, self.alpha) / (4.0 * cos_om)
        ok &= np.isfinite(ratio) & np.isfinite(pdf) & (pdf > 0)
        weight = where_rows(ok, ratio[:, None] * self.fresnel(cos_om, lam), 0.0)
        return BSDFSample(wi, weight, np.where(ok, pdf, 0.0), np.zeros(n, dtype=bool), np.ones(n))
