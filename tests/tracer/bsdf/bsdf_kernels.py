"""Compiled loops that run a material's BSDF over many inputs, for the statistical tests (not a test module).

The material is resolved as the render resolves it: constant rows, then, for Multiscatter GGX closures,
the energy compensation seen from ``wo`` (``materials.energy``; below the surface is inside a glass); fibres get
their parameters and absorption (``materials.hair_setup``) with the tangent and h the test wrote in the rows."""

from engine.tracer.bsdf.dispatch import bsdf_evaluate, bsdf_sample
from engine.tracer.jit import inlined, kernel
from engine.tracer.materials.energy import compensate_energy
from engine.tracer.materials.resolve import resolve_material
from engine.tracer.materials.sheen_setup import set_up_sheen
from engine.tracer.bsdf.closure import C_KIND, HAIR
from engine.tracer.materials.hair_setup import hair_parameters
from engine.tracer.materials.table import MAT_HAIR, MAT_MULTISCATTER, MAT_SHEEN


@inlined
def _resolve(materials, spectra, wo, lam, hero, rows, spectral, eta, clamps):
    count = resolve_material(materials, spectra, 0, lam, hero, rows, spectral, eta, clamps)
    if materials.flags[0] & MAT_MULTISCATTER:
        compensate_energy(materials, spectra, materials.programs.tables.energy, rows, spectral, eta, count, wo[2],
                          wo[2] < 0.0, lam, materials.programs.constants)
    if materials.flags[0] & MAT_SHEEN:
        set_up_sheen(materials.programs.tables.sheen, rows, spectral, count, wo[2])
    if materials.flags[0] & MAT_HAIR:  # the fibre's tangent and h stay as the test set them in the rows
        for c in range(count):
            if int(rows[c, C_KIND]) == HAIR:
                hair_parameters(rows[c], spectral[c], lam)
    return count


@kernel
def sample_many(materials, spectra, wo, lam, u, hero, collapsed, wi, weight, pdf, flags, eta_scale, eta_out, work,
                clamps):
    rows, spectral, eta, _, _, _, scratch, _, _ = work
    for i in range(wo.shape[0]):
        count = _resolve(materials, spectra, wo[i], lam[i], hero[i], rows, spectral, eta, clamps)
        eta_out[i] = eta[0]
        w, p, f, e, _ = bsdf_sample(rows, spectral, eta, count, (wo[i, 0], wo[i, 1], wo[i, 2]), lam[i], hero[i],
                                    collapsed[i], u[i, 0], u[i, 1], u[i, 2], weight[i], scratch)
        wi[i, 0], wi[i, 1], wi[i, 2] = w
        pdf[i] = p
        flags[i] = f
        eta_scale[i] = e


@kernel
def evaluate_many(materials, spectra, wo, wi, lam, hero, collapsed, f, pdf, work, clamps):
    rows, spectral, eta, _, _, _, scratch, _, _ = work
    for i in range(wo.shape[0]):
        count = _resolve(materials, spectra, wo[i], lam[i], hero[i], rows, spectral, eta, clamps)
        pdf[i] = bsdf_evaluate(rows, spectral, eta, count, (wo[i, 0], wo[i, 1], wo[i, 2]),
                               (wi[i, 0], wi[i, 1], wi[i, 2]), lam[i], hero[i], collapsed[i], f[i], scratch)
