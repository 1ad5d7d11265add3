"""Lambertian reflection: f = albedo(lambda) / pi, cosine-weighted sampling."""

from __future__ import annotations

import numpy as np

from ..sampling import cosine_hemisphere, where_rows
from .base import BSDF, BSDFSample


def _eval(albedo, wo, wi):
    ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
    f = where_rows(ok, albedo / np.pi, 0.0)
    return f, np.where(ok, wi[:, 2] / np.pi, 0.0)


def _sample(albedo_of_lam, wo, lam, u):
    n = len(wo)
    wi = cosine_hemisphere(u[:, 1:3])
    ok = (wo[:, 2] > 0) & (wi[:, 2] > 0)
    weight = where_rows(ok, albedo_of_lam(lam), 0.0)
    return BSDFSample(wi, weight, np.where(ok, wi[:, 2] / np.pi, 0.0), np.zeros(n, dtype=bool), np.ones(n))


class Diffuse(BSDF):
    kind = "diffuse"

    def __init__(self, albedo):
        """``albedo``: callable wavelength_nm [n,K] -> reflectance [n,K]."""
        self.albedo = albedo

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        return _eval(self.albedo(lam), wo, wi)

    def sample(self, wo, lam, u, hero, collapsed):
        return _sample(self.albedo, wo, lam, u)


class DiffuseSet:
    """Several ``Diffuse`` materials shaded in one call (same results row for row).

    Each row's albedo is one gather from a per-chunk table of all members' albedos
    stacked, instead of a sort by material, per-material gathers of every input and
    an un-permutation of every output (a Cornell box has 3-5 diffuse materials)."""

    def __init__(self, members: dict, material_count: int):
        """``members``: material index -> ``Diffuse``; ``material_count``: size of the index space."""
        self.members = list(members.values())
        self.slot = np.zeros(material_count, dtype=np.int64)
        for s, m in enumerate(members):
            self.slot[m] = s

    def albedo(self, mat, lam):
        """Reflectance [n,K] of each row's material ``mat`` [n] at its wavelengths."""
        rows = getattr(lam, "_rows", None)
        if rows is None:
            slot = self.slot[mat]
            out = np.empty(np.shape(lam))
            for s, member in enumerate(self.members):
                sel = np.flatnonzero(slot == s)
                if len(sel):
                    out[sel] = member.albedo(np.asarray(lam)[sel])
            return out
        key = (self, "stacked albedo")
        table = lam._cache.get(key)
        if table is None:  # once per chunk: every member over all of the chunk's paths
            whole = lam.whole_chunk()
            table = lam._cache[key] = np.concatenate([np.asarray(m.albedo(whole), dtype=np.float64)
                                                      for m in self.members])
        return np.take(table, self.slot[mat] * len(lam._full) + rows, axis=0)

    def eval(self, mat, wo, wi, lam, hero=None, collapsed=None):
        return _eval(self.albedo(mat, lam), wo, wi)

    def sample(self, mat, wo, lam, u, hero, collapsed):
        return _sample(lambda wl: self.albedo(mat, wl), wo, lam, u)
