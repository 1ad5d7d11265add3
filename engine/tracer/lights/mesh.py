"""Emissive triangles (materials with ``emission_strength`` > 0) as one light.

Emission is two-sided with radiance strength x spectrum (Cycles' Emission). For
next-event estimation a triangle is picked with probability proportional to
area x strength and a point uniformly on it; densities are converted to solid
angle so BSDF-sampled hits on the same triangles can be weighted by MIS.
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot, uniform_triangle, where_rows


class MeshEmitters:
    delta = False
    hittable = False
    name = "emissive meshes"

    def __init__(self, vertices, triangles, emissive_triangles, strengths, spectrum_ids, spectra, triangle_count):
        """``emissive_triangles`` [m] indexes ``triangles``; ``strengths`` [m];
        ``spectrum_ids`` [m] indexes ``spectra`` (callables lambda [n,K] -> [n,K])."""
        self.triangles = np.asarray(emissive_triangles, dtype=np.int64)
        corners = np.asarray(vertices, dtype=np.float64)[np.asarray(triangles)[self.triangles]]
        self.v0 = corners[:, 0]
        self.e1 = corners[:, 1] - corners[:, 0]
        self.e2 = corners[:, 2] - corners[:, 0]
        cross = np.cross(self.e1, self.e2)
        double_area = np.linalg.norm(cross, axis=1)
        self.area = 0.5 * double_area
        self.normal = cross / np.where(double_area > 0, double_area, 1.0)[:, None]
        self.strength = np.asarray(strengths, dtype=np.float64)
        self.spectrum_ids = np.asarray(spectrum_ids, dtype=np.int64)
        self.spectra = list(spectra)
        weight = self.area * self.strength
        self.total = float(weight.sum())
        self.cdf = np.cumsum(weight) / self.total if self.total > 0 else np.linspace(0, 1, len(weight) + 1)[1:]
        self.select = weight / self.total if self.total > 0 else np.zeros(len(weight))
        self.row_of_triangle = np.full(int(triangle_count), -1, dtype=np.int64)
        self.row_of_triangle[self.triangles] = np.arange(len(self.triangles))

    def _radiance_rows(self, rows, lam):
        out = np.zeros(lam.shape)
        sid = self.spectrum_ids[rows]
        for s in np.unique(sid):
            m = sid == s
            out[m] = self.strength[rows[m], None] * self.spectra[s](lam[m])
        return out

    def sample(self, p, u, lam):
        rows = np.minimum(np.searchsorted(self.cdf, u[:, 2], side="right"), len(self.cdf) - 1)
        b = uniform_triangle(u[:, :2])
        q = self.v0[rows] + b[:, 0:1] * self.e1[rows] + b[:, 1:2] * self.e2[rows]
        wi = q - p
        dist = np.sqrt(dot(wi, wi))
        safe = np.where(dist > 0, dist, 1.0)
        wi = wi / safe[:, None]
        cos_l = np.abs(dot(wi, self.normal[rows]))
        ok = (cos_l > 0) & (dist > 0) & (self.area[rows] > 0)
        area = np.where(ok, self.area[rows], 1.0)
        pdf = np.where(ok, self.select[rows] / area * safe**2 / np.where(ok, cos_l, 1.0), 0.0)
        li = where_rows(ok, self._radiance_rows(rows, lam), 0.0)
        return wi, dist, li, pdf

    def radiance(self, triangle, lam):
        """Emitted radiance [n,K] of hit triangles (original indices; 0 if not emissive)."""
        rows = self.row_of_triangle[triangle]
        out = np.zeros(lam.shape)
        ok = rows >= 0
        if ok.any():
            out[ok] = self._radiance_rows(rows[ok], lam[ok])
        return out

    def pdf(self, o, d, t, triangle):
        """Solid-angle density of ``sample`` for rays from ``o`` hitting ``triangle`` at ``t``."""
        rows = self.row_of_triangle[triangle]
        ok = rows >= 0
        r = np.where(ok, rows, 0)
        cos_l = np.abs(dot(d, self.normal[r]))
        with np.errstate(divide="ignore", invalid="ignore"):
            pdf = self.select[r] / self.area[r] * t * t / cos_l
        return np.where(ok & np.isfinite(pdf), pdf, 0.0)
