"""DiffuseSet (several Lambertian materials in one call) matches each Diffuse row for row."""

import numpy as np

from engine.tracer import path_spectra as spectra
from engine.tracer.bsdf.diffuse import Diffuse, DiffuseSet
from engine.tracer.path_state import compact
from engine.tracer.path_spectra import PathWavelengths


def _members():
    return {1: Diffuse(spectra.reflectance((0.63, 0.065, 0.05))), 3: Diffuse(spectra.reflectance((0.14, 0.45, 0.09))),
            4: Diffuse(spectra.reflectance((0.0, 0.0, 0.0)))}


def _inputs(n=400, k=4, seed=1):
    rng = np.random.default_rng(seed)
    wo = rng.normal(size=(n, 3))
    wi = rng.normal(size=(n, 3))
    lam = rng.uniform(380.0, 720.0, size=(n, k))
    mat = rng.choice([1, 3, 4], size=n)
    return rng, wo / np.linalg.norm(wo, axis=1, keepdims=True), wi / np.linalg.norm(wi, axis=1, keepdims=True), lam, mat


def _reference(members, method, mat, *args):
    outs = None
    for m, bsdf in members.items():
        rows = np.flatnonzero(mat == m)
        sub = [a[rows] for a in args]
        res = bsdf.sample(*sub, None, None) if method == "sample" else bsdf.eval(*sub)
        res = (res.wi, res.weight, res.pdf) if method == "sample" else res
        if outs is None:
            outs = [np.zeros((len(mat),) + r.shape[1:], r.dtype) for r in res]
        for o, r in zip(outs, res):
            o[rows] = r
    return outs


def test_eval_and_sample_match_members_with_plain_and_linked_wavelengths():
    members = _members()
    diffuse_set = DiffuseSet(members, 6)
    rng, wo, wi, lam, mat = _inputs()
    u = rng.random((len(mat), 3))
    keep = rng.random(len(mat)) < 0.7
    linked = compact(keep, PathWavelengths(lam))[0]  # a compacted chunk: rows looked up in the cache
    wo, wi, mat, u, plain = compact(keep, wo, wi, mat, u, lam)
    for wl in (plain, linked):
        f, pdf = diffuse_set.eval(mat, wo, wi, wl)
        f_ref, pdf_ref = _reference(members, "eval", mat, wo, wi, plain)
        np.testing.assert_array_equal(f, f_ref)
        np.testing.assert_array_equal(pdf, pdf_ref)
        s = diffuse_set.sample(mat, wo, wl, u, None, None)
        wi_ref, weight_ref, spdf_ref = _reference(members, "sample", mat, wo, plain, u)
        np.testing.assert_array_equal(s.wi, wi_ref)
        np.testing.assert_array_equal(s.weight, weight_ref)
        np.testing.assert_array_equal(s.pdf, spdf_ref)
    assert np.all(f[mat == 4] == 0.0) and np.all(f[(mat == 1) & (pdf > 0)] > 0)
