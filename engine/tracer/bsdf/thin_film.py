"""Free-standing thin film (soap bubble): a layer of index ``film_ior`` and thickness
``film_thickness_nm`` in air. Both faces are parallel, so the transmitted ray leaves
undeviated (wi = -wo); reflection is specular. Airy reflectance R(lambda, theta)
per wavelength, T = 1 - R (no absorption). Both lobes are deltas; the lobe is
chosen with p = mean R over the carried wavelengths, weights R_j/p, T_j/(1-p).
"""

from __future__ import annotations

import numpy as np

from ..sampling import where_rows
from .base import BSDF, BSDFSample
from .dielectric import choice_probability


class ThinFilm(BSDF):
    kind = "thin_film"
    delta = True

    def __init__(self, reflectance):
        """``reflectance(cos_i [n], lam [n,K]) -> R [n,K]`` of the film in air."""
        self.reflectance = reflectance

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        n, k = lam.shape
        return np.zeros((n, k)), np.zeros(n)

    def sample(self, wo, lam, u, hero, collapsed):
        n = len(wo)
        r = np.clip(self.reflectance(np.clip(np.abs(wo[:, 2]), 0.0, 1.0), lam), 0.0, 1.0)
        p = choice_probability(r, hero, collapsed)
        reflect = u[:, 0] < p
        wi = where_rows(reflect, wo * np.array([-1.0, -1.0, 1.0]), -wo)
        with np.errstate(divide="ignore", invalid="ignore"):
            weight = where_rows(reflect, r / p[:, None], (1.0 - r) / (1.0 - p[:, None]))
        weight = np.where(np.isfinite(weight), weight, 0.0)
        return BSDFSample(wi, weight, np.full(n, np.inf), np.ones(n, dtype=bool), np.ones(n))
