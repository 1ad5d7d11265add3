"""Lambertian reflection: f = albedo(lambda) / pi, cosine-weighted sampling."""

from __future__ import annotations

import numpy as np

from ..sampling import cosine_hemisphere, where_rows
from .base import BSDF, BSDFSample


class Diffuse(BSDF):
    kind = "diffuse"

    def __init__(self, albedo):
        """``albedo``: callable wavelength_nm [n,K] -> reflectance [n,K]."""
        self.albedo = albedo

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
        f = where_rows(ok, self.albedo(lam) / np.pi, 0.0)
        return f, np.where(ok, wi[:, 2] / np.pi, 0.0)

    def sample(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        wi = cosine_hemisphere(u[:, 1:3])
        ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
        weight = where_rows(ok, self.albedo(lam), 0.0)
        return BSDFSample(wi, weight, np.where(ok, wi[:, 2] / np.pi, 0.0), np.zeros(n, dtype=bool), np.ones(n))
