"""Shared statistical checks for BSDF tests (not a test module).

``MaterialBSDF(material)`` is a ``scene.Material``'s BSDF exactly as the render kernels run it
(material table, spectra resolved at the sampled wavelengths, ``bsdf.dispatch``), vectorised.

``chi2_sampling_test``: draws directions with ``bsdf.sample`` and compares their
histogram in (cos theta, phi) with the integral of ``bsdf.eval``'s pdf over each
bin (Gauss-Legendre quadrature). Each lobe gets its own zoomed rectangle (1st to
99th percentile of its samples, so very sharp lobes such as GGX alpha = 0.01
still fall on many bins); everything else is pooled, and bins expecting fewer
than 5 samples are merged, as in Mitsuba's chi-square tests.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from scipy import stats

from engine.tracer.bsdf.closure import SAMPLED_DELTA
from engine.tracer.materials.table import MAT_DELTA, MAT_DISPERSIVE, build_materials
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.state import new_shading_scratch

from .bsdf_kernels import evaluate_many, sample_many


class MaterialBSDF:
    """``sample(wo, lam, u, hero, collapsed)`` and ``eval(wo, wi, lam, hero, collapsed)`` over rows."""

    def __init__(self, material, table=None):
        spectra = SpectrumTable()
        self.table = table or build_materials([material], {0}, spectra)
        self.spectra = spectra.arrays()
        self.delta = bool(self.table.arrays.flags[0] & MAT_DELTA)
        self.disperses = bool(self.table.arrays.flags[0] & MAT_DISPERSIVE)

    def sample(self, wo, lam, u, hero, collapsed):
        n, k = np.shape(lam)
        out = SimpleNamespace(wi=np.empty((n, 3)), weight=np.empty((n, k)), pdf=np.empty(n),
                              flags=np.empty(n, np.int64), eta_scale=np.empty(n), eta=np.empty(n))
        sample_many(self.table.arrays, self.spectra, np.ascontiguousarray(wo, dtype=np.float64),
                    np.ascontiguousarray(lam, dtype=np.float64), np.ascontiguousarray(u, dtype=np.float64),
                    np.asarray(hero, np.int64), np.asarray(collapsed, bool), out.wi, out.weight, out.pdf, out.flags,
                    out.eta_scale, out.eta, new_shading_scratch(k), self._clamps())
        out.delta = (out.flags & SAMPLED_DELTA) != 0
        out.pdf = np.where(np.isinf(out.pdf), np.inf, out.pdf)
        return out

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        n, k = np.shape(lam)
        hero = np.zeros(n, np.int64) if hero is None else np.asarray(hero, np.int64)
        collapsed = np.zeros(n, bool) if collapsed is None else np.asarray(collapsed, bool)
        f, pdf = np.empty((n, k)), np.empty(n)
        evaluate_many(self.table.arrays, self.spectra, np.ascontiguousarray(wo, dtype=np.float64),
                      np.ascontiguousarray(wi, dtype=np.float64), np.ascontiguousarray(lam, dtype=np.float64), hero,
                      collapsed, f, pdf, new_shading_scratch(k), self._clamps())
        return f, pdf

    def _clamps(self):
        return np.zeros(len(self.table.arrays.glasses), np.int64)

    def eta(self, lam, hero):
        """The resolved glass index per row (at the hero wavelength for a dispersive glass)."""
        n = len(lam)
        return self.sample(np.tile([0.0, 0.0, 1.0], (n, 1)), lam, np.full((n, 3), 0.5), hero, np.ones(n, bool)).eta


def mixture(materials, weights, set_rows=None):
    """One material whose closures are those of ``materials`` with ``weights``; ``set_rows(closures)`` may
    change the rows first."""
    from engine.tracer.bsdf.closure import C_TINT, C_WEIGHT
    from engine.tracer.materials.table import MaterialTable

    spectra = SpectrumTable()
    table = build_materials(materials, set(range(len(materials))), spectra)
    a = table.arrays
    closures = a.closures.copy()
    closures[:, C_WEIGHT] = weights
    closures[:, C_TINT] = [spectra.constant(w) for w in weights]
    if set_rows is not None:
        set_rows(closures)
    arrays = a._replace(flags=a.flags[:1] * 0, closure_start=np.zeros(1, np.int32),
                        closure_count=np.array([len(materials)], np.int32), closures=closures)
    bsdf = MaterialBSDF(None, MaterialTable(arrays, table.glasses, table.features))
    bsdf.spectra = spectra.arrays()
    return bsdf


def direction(theta_deg, phi_deg=30.0, below=False):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    v = np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])
    if below:
        v[2] = -v[2]
    return v


def _angles(w, phi0):
    phi = np.mod(np.arctan2(w[:, 1], w[:, 0]) - phi0 + np.pi, 2 * np.pi) - np.pi
    return w[:, 2], phi


def _to_dir(cos, phi, phi0):
    s = np.sqrt(np.maximum(0.0, 1 - cos * cos))
    return np.stack([s * np.cos(phi + phi0), s * np.sin(phi + phi0), cos], -1)


def chi2_sampling_test(bsdf, wo, n=300_000, bins=24, lam=550.0, seed=0, quad=12):
    """p-value of the chi-square test of the sampled directions against the pdf."""
    rng = np.random.default_rng(seed)
    wo_n = np.repeat(wo[None], n, 0)
    lam_n = np.full((n, 1), lam)
    hero = np.zeros(n, dtype=np.int64)
    coll = np.zeros(n, dtype=bool)
    s = bsdf.sample(wo_n, lam_n, rng.random((n, 3)), hero, coll)
    valid = (s.pdf > 0) & (s.weight > 0).any(1)
    wi = s.wi[valid]
    phi0 = np.arctan2(wo[1], wo[0]) + np.pi  # lobes sit opposite wo in azimuth
    cos, phi = _angles(wi, phi0)
    observed, expected = [], []
    claimed = np.zeros(len(wi), dtype=bool)
    gx, gw = np.polynomial.legendre.leggauss(quad)
    for lobe in (cos > 0, cos < 0):
        if lobe.sum() < 100:
            continue
        c_lo, c_hi = np.percentile(cos[lobe], [0.5, 99.5])
        p_lo, p_hi = np.percentile(phi[lobe], [0.5, 99.5])
        c_lo, c_hi = (max(c_lo, -1.0), min(c_hi, 1.0)) if c_hi > c_lo else (c_lo - 1e-3, c_hi + 1e-3)
        ce = np.linspace(c_lo, c_hi, bins + 1)
        pe = np.linspace(max(p_lo, -np.pi), min(p_hi, np.pi), bins + 1)
        inside = (cos >= ce[0]) & (cos < ce[-1]) & (phi >= pe[0]) & (phi < pe[-1]) & ~claimed
        claimed |= inside
        h, _, _ = np.histogram2d(cos[inside], phi[inside], bins=[ce, pe])
        # quadrature nodes of every bin
        cc = (0.5 * (ce[1:] - ce[:-1])[:, None] * gx[None] + 0.5 * (ce[1:] + ce[:-1])[:, None])  # [b, q]
        pp = (0.5 * (pe[1:] - pe[:-1])[:, None] * gx[None] + 0.5 * (pe[1:] + pe[:-1])[:, None])
        C = cc[:, None, :, None] * np.ones((1, bins, 1, quad))
        P = pp[None, :, None, :] * np.ones((bins, 1, quad, 1))
        wi_q = _to_dir(C.ravel(), P.ravel(), phi0)
        m = len(wi_q)
        _, pdf = bsdf.eval(np.repeat(wo[None], m, 0), wi_q, np.full((m, 1), lam), np.zeros(m, dtype=np.int64),
                           np.zeros(m, dtype=bool))
        w = (gw[:, None] * gw[None, :])[None, None]
        area = (0.25 * (ce[1:] - ce[:-1])[:, None] * (pe[1:] - pe[:-1])[None, :])
        mass = (pdf.reshape(bins, bins, quad, quad) * w).sum((2, 3)) * area
        observed.append(h.ravel())
        expected.append(mass.ravel() * n)
    observed = np.concatenate(observed)
    expected = np.concatenate(expected)
    # everything outside the rectangles and the failed samples: one pooled bin
    rest_obs = n - observed.sum()
    rest_exp = n - expected.sum()
    order = np.argsort(expected)
    obs_s, exp_s = observed[order], expected[order]
    small = exp_s < 5
    obs_f = list(obs_s[~small]) + [obs_s[small].sum() + rest_obs]
    exp_f = list(exp_s[~small]) + [exp_s[small].sum() + rest_exp]
    obs_f, exp_f = np.array(obs_f), np.array(exp_f)
    if exp_f[-1] < 5:  # merge the pooled bin into the smallest proper bin
        obs_f[-2] += obs_f[-1]
        exp_f[-2] += exp_f[-1]
        obs_f, exp_f = obs_f[:-1], exp_f[:-1]
    chi2 = ((obs_f - exp_f) ** 2 / exp_f).sum()
    return float(stats.chi2.sf(chi2, len(obs_f) - 1))


def albedo(bsdf, wo, n=200_000, lam=None, seed=1):
    """Monte Carlo directional albedo per wavelength column (mean sample weight)."""
    rng = np.random.default_rng(seed)
    lam = np.full((n, 1), 550.0) if lam is None else np.broadcast_to(lam, (n, len(lam))).copy()
    s = bsdf.sample(np.repeat(wo[None], n, 0), lam, rng.random((n, 3)), np.zeros(n, dtype=np.int64),
                    np.zeros(n, dtype=bool))
    return s.weight.mean(0)


def weight_matches_eval(bsdf, wo, n=2000, seed=2):
    """Max relative mismatch between sample weights and f |cos| / pdf from eval."""
    rng = np.random.default_rng(seed)
    lam = np.full((n, 1), 550.0)
    hero = np.zeros(n, dtype=np.int64)
    coll = np.zeros(n, dtype=bool)
    wo_n = np.repeat(wo[None], n, 0)
    s = bsdf.sample(wo_n, lam, rng.random((n, 3)), hero, coll)
    ok = s.pdf > 0
    f, pdf = bsdf.eval(wo_n[ok], s.wi[ok], lam[ok], hero[ok], coll[ok])
    expect = f[:, 0] * np.abs(s.wi[ok, 2]) / pdf
    rel_w = np.abs(expect - s.weight[ok, 0]) / np.maximum(expect, 1e-12)
    rel_p = np.abs(pdf - s.pdf[ok]) / pdf
    return float(max(rel_w.max(initial=0), rel_p.max(initial=0)))
