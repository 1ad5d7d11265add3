"""Compiled loops that run a material's BSDF over many inputs, for the statistical tests (not a test module)."""

from engine.tracer.bsdf.dispatch import bsdf_evaluate, bsdf_sample
from engine.tracer.jit import kernel
from engine.tracer.materials.resolve import resolve_material


@kernel
def sample_many(materials, spectra, wo, lam, u, hero, collapsed, wi, weight, pdf, flags, eta_scale, eta_out, work,
                clamps):
    rows, spectral, eta, _, _, _, scratch, _, _ = work
    for i in range(wo.shape[0]):
        count = resolve_material(materials, spectra, 0, lam[i], hero[i], rows, spectral, eta, clamps)
        eta_out[i] = eta[0]
        w, p, f, e = bsdf_sample(rows, spectral, eta, count, (wo[i, 0], wo[i, 1], wo[i, 2]), lam[i], hero[i],
                                 collapsed[i], u[i, 0], u[i, 1], u[i, 2], weight[i], scratch)
        wi[i, 0], wi[i, 1], wi[i, 2] = w
        pdf[i] = p
        flags[i] = f
        eta_scale[i] = e


@kernel
def evaluate_many(materials, spectra, wo, wi, lam, hero, collapsed, f, pdf, work, clamps):
    rows, spectral, eta, _, _, _, scratch, _, _ = work
    for i in range(wo.shape[0]):
        count = resolve_material(materials, spectra, 0, lam[i], hero[i], rows, spectral, eta, clamps)
        pdf[i] = bsdf_evaluate(rows, spectral, eta, count, (wo[i, 0], wo[i, 1], wo[i, 2]),
                               (wi[i, 0], wi[i, 1], wi[i, 2]), lam[i], hero[i], collapsed[i], f[i], scratch)
