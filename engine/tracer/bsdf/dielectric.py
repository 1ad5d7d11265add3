"""Dielectric interfaces (glass): smooth (delta) or rough GGX, optionally coated.

The local frame's +Z is the outward normal: wo.z > 0 means the ray arrives from
outside (index 1), wo.z < 0 from inside the glass. ``eta`` is the glass index at
the path's hero wavelength when the glass disperses (the integrator has then kept
only the hero wavelength), otherwise its constant index. Refracted radiance is
scaled by 1/eta'^2 (non-symmetric transport for radiance, Veach 1997 §5.2).

Reflection vs refraction is chosen with probability p = mean reflectance over the
carried wavelengths (hero only once collapsed); each column is weighted R_j / p or
(1 - R_j) / (1 - p). Rough transmission follows Walter et al. 2007 with
visible-normal sampling (Heitz 2018).
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot, norm, row_sum, rows_finite, where_rows

from .base import BSDF, BSDFSample, hero_column
from .microfacet import ggx_d, ggx_g1, ggx_g2, sample_visible_normal, visible_normal_pdf
from .microfacet import reflect as mirror
from .optics import fresnel_dielectric, refract

SMOOTH_ALPHA = 1e-3


def choice_probability(r: np.ndarray, hero: np.ndarray, collapsed: np.ndarray) -> np.ndarray:
    """Probability [n] of picking reflection given per-column reflectances [n,K]."""
    return np.clip(np.where(collapsed, hero_column(r, hero), row_sum(r) / r.shape[1]), 0.0, 1.0)


class Dielectric(BSDF):
    kind = "dielectric"
    two_sided = False

    def __init__(self, glass, alpha: float, coating=None):
        """``glass`` has ``index(lambda_nm)`` and ``is_dispersive``; ``coating`` is None or a
        callable (cos_i [n], eta_outside [n], eta_inside [n], lam [n,K]) -> R [n,K]."""
        self.glass = glass
        self.disperses = bool(glass.is_dispersive)
        self.alpha = float(alpha)
        self.delta = self.alpha < SMOOTH_ALPHA
        self.coating = coating
        self._constant_eta = None if self.disperses else float(np.asarray(glass.index(550.0)))

    def eta(self, lam, hero):
        """Relative index (glass / outside) per path [n]."""
        if self._constant_eta is not None:
            return np.full(len(lam), self._constant_eta)
        return np.asarray(self.glass.index(hero_column(lam, hero)), dtype=np.float64)

    def reflectance(self, cos_i, eta, lam):
        """R [n,K] for a wave arriving with signed cosine ``cos_i`` (< 0: from inside)."""
        if self.coating is None:
            return np.broadcast_to(fresnel_dielectric(cos_i, eta)[:, None], lam.shape)
        outside = cos_i >= 0
        n_in = np.where(outside, 1.0, eta)
        n_out = np.where(outside, eta, 1.0)
        return self.coating(np.abs(cos_i), n_in, n_out, lam)

    def sample(self, wo, lam, u, hero, collapsed):
        if self.delta:
            return self._sample_smooth(wo, lam, u, hero, collapsed)
        return self._sample_rough(wo, lam, u, hero, collapsed)

    def eval(self, wo, wi, lam, hero, collapsed):
        n, k = lam.shape
        if self.delta:
            return np.zeros((n, k)), np.zeros(n)
        return self._eval_rough(wo, wi, lam, hero, collapsed)

    def _sample_smooth(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        eta = self.eta(lam, hero)
        r = self.reflectance(wo[:, 2], eta, lam)
        p = choice_probability(r, hero, collapsed)
        wt, etap, tir = refract(wo, np.broadcast_to([0.0, 0.0, 1.0], (n, 3)), eta)
        reflect = (u[:, 0] < p) | tir
        wi = where_rows(reflect, wo * np.array([-1.0, -1.0, 1.0]), wt)
        with np.errstate(divide="ignore", invalid="ignore"):
            w_r = where_rows(tir, 1.0, r / p[:, None])
            w_t = (1.0 - r) / (1.0 - p[:, None]) / (etap * etap)[:, None]
        weight = where_rows(reflect, w_r, w_t)
        weight = np.where(np.isfinite(weight), weight, 0.0)
        eta_scale = np.where(reflect, 1.0, etap * etap)
        return BSDFSample(wi, weight, np.full(n, np.inf), np.ones(n, dtype=bool), eta_scale)

    def _sample_rough(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        eta = self.eta(lam, hero)
        wm = sample_visible_normal(wo, self.alpha, u[:, 1:3])
        cos_om = dot(wo, wm)
        r = self.reflectance(cos_om, eta, lam)
        p = choice_probability(r, hero, collapsed)
        reflect = u[:, 0] < p
        wi_r = mirror(wo, wm)
        wi_t, etap, tir = refract(wo, wm, eta)
        wi = where_rows(reflect, wi_r, wi_t)
        cos_i = wi[:, 2]
        valid = np.where(reflect, wo[:, 2] * cos_i > 0, (~tir) & (wo[:, 2] * cos_i < 0))
        ratio = ggx_g2(wo, wi, self.alpha) / ggx_g1(wo, self.alpha)
        pdf_wm = visible_normal_pdf(wo, wm, self.alpha)
        cos_im = dot(wi, wm)
        with np.errstate(divide="ignore", invalid="ignore"):
            denom = (cos_im + cos_om / etap) ** 2
            pdf = np.where(
                reflect, pdf_wm / (4.0 * np.abs(cos_om)) * p, pdf_wm * np.abs(cos_im) / denom * (1.0 - p)
            )
            w = np.where(
                reflect[:, None], r / p[:, None], (1.0 - r) / (1.0 - p[:, None]) / (etap * etap)[:, None]
            )
        weight = ratio[:, None] * w
        valid &= np.isfinite(pdf) & (pdf > 0) & rows_finite(weight)
        eta_scale = np.where(reflect, 1.0, etap * etap)
        return BSDFSample(
            wi, where_rows(valid, weight, 0.0), np.where(valid, pdf, 0.0), np.zeros(n, dtype=bool), eta_scale
        )

    def _eval_rough(self, wo, wi, lam, hero, collapsed):
        n, k = lam.shape
        eta = self.eta(lam, hero)
        cos_o, cos_i = wo[:, 2], wi[:, 2]
        reflect = cos_o * cos_i > 0
        etap = np.where(reflect, 1.0, np.where(cos_o > 0, eta, 1.0 / eta))
        wm = wi * etap[:, None] + wo
        length = norm(wm)
        ok = (cos_o != 0) & (cos_i != 0) & (length > 0)
        wm = wm / np.where(length > 0, length, 1.0)[:, None]
        wm *= np.where(wm[:, 2] < 0, -1.0, 1.0)[:, None]
        cos_om = dot(wo, wm)
        cos_im = dot(wi, wm)
        ok &= (cos_im * cos_i > 0) & (cos_om * cos_o > 0)
        r = self.reflectance(cos_om, eta, lam)
        p = choice_probability(r, hero, collapsed)
        d = ggx_d(wm, self.alpha)
        g = ggx_g2(wo, wi, self.alpha)
        pdf_wm = visible_normal_pdf(wo, wm, self.alpha)
        with np.errstate(divide="ignore", invalid="ignore"):
            denom = (cos_im + cos_om / etap) ** 2
            f_r = (d * g / (4.0 * np.abs(cos_i * cos_o)))[:, None] * r
            f_t = d * g * np.abs(cos_im * cos_om) / (np.abs(cos_i * cos_o) * denom) / (etap * etap)
            f_t = f_t[:, None] * (1.0 - r)
            pdf = np.where(reflect, pdf_wm / (4.0 * np.abs(cos_om)) * p, pdf_wm * np.abs(cos_im) / denom * (1.0 - p))
        f = where_rows(reflect, f_r, f_t)
        ok &= np.isfinite(pdf) & rows_finite(f)
        return where_rows(ok, f, 0.0), np.where(ok, pdf, 0.0)
