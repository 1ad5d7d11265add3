"""Blender's Hair BSDF (``bsdf.hair_kajiya`` through ``bsdf.dispatch``), as Cycles' ``bsdf_hair.h`` computes it,
inconsistencies included: a sample's weight is 1; eval's value is its pdf; Transmission's sample pdf is eval's
where eval answers. Reflection's sample pdf is cos(φ/2) / (4 r2) in azimuth while its sampler's density (and
eval) is cos(φ/(2 r2)) / (4 r2); Transmission's eval does not stop at the ±π/2 its sampler covers, so it integrates
to more than the samples that land where it answers (measured for RoughnessU 0.1, RoughnessV 0.2 at 30°: 0.9918
against 0.9822) — both as in Cycles, whose sample weight (eval / pdf = 1) hides them from the image."""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ, HAIR
from engine.tracer.bsdf.hair_kajiya import REFLECTION, TRANSMISSION
from engine.tracer.materials.shader import ClosureSpec, Colour, HairInputs, ShaderProgram
from engine.tracer.scene import Material

from .bsdf_checks import MaterialBSDF, direction
from .test_hair import _sphere_integral


def _kajiya(component, r1, r2, offset=0.0):
    hair = HairInputs(model=component, roughness=r1, radial_roughness=r2, offset=offset)
    spec = ClosureSpec(HAIR, tint=Colour(rgb=(1.0, 1.0, 1.0)), alpha=1.0, hair=hair)
    bsdf = MaterialBSDF(Material("hair", shader=ShaderProgram([spec])))
    rows = bsdf.table.arrays.closures
    rows[0, C_HAIR_TX], rows[0, C_HAIR_TY], rows[0, C_HAIR_TZ] = 1.0, 0.0, 0.0  # along the surface, as on a curve
    return bsdf


@pytest.mark.parametrize("component", [REFLECTION, TRANSMISSION])
@pytest.mark.parametrize("r1, r2, offset", [(0.1, 0.2, 0.0), (0.3, 0.4, 0.05), (0.6, 0.45, -0.1)])
@pytest.mark.parametrize("theta", [30.0, 70.0])
def test_samples_agree_with_eval(component, r1, r2, offset, theta):
    bsdf = _kajiya(component, r1, r2, offset)
    wo = direction(theta, phi_deg=60.0)
    n = 200_000
    rng = np.random.default_rng(7)
    lam = np.full((n, 1), 550.0)
    s = bsdf.sample(np.repeat(wo[None], n, 0), lam, rng.random((n, 3)), np.zeros(n, np.int64), np.zeros(n, bool))
    valid = s.pdf > 0
    assert valid.mean() > 0.99
    assert np.all(s.weight[valid] == 1.0)
    f, pdf = bsdf.eval(np.repeat(wo[None], n, 0)[valid], s.wi[valid], lam[valid])
    kept = pdf > 0
    assert kept.mean() > 0.5
    np.testing.assert_allclose(f[kept, 0] * np.abs(s.wi[valid][kept, 2]), pdf[kept], rtol=1e-9)
    if component == TRANSMISSION:
        np.testing.assert_allclose(pdf[kept], s.pdf[valid][kept], rtol=1e-6)
    assert _sphere_integral(bsdf, wo, nx=400, nphi=800) < (1.2 if component == TRANSMISSION else 1.0 + 1e-3)
