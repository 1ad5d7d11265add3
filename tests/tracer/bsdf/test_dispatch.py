"""A material of several closures (f = Σ t_i f_i, sampled ∝ w_i): sampling matches the mixture's pdf (chi-square),
weights match f |cos| / pdf, and delta closures keep their share."""

import numpy as np
import pytest

from engine.tracer.scene import Material

from .bsdf_checks import albedo, chi2_sampling_test, direction, mixture, weight_matches_eval

DIFFUSE = Material("white", base_color=(0.8, 0.8, 0.8))
ROUGH_METAL = Material("metal", kind="conductor", base_color=(1.0, 1.0, 1.0), roughness=0.4)
MIRROR = Material("mirror", kind="conductor", base_color=(1.0, 1.0, 1.0))


@pytest.mark.parametrize("theta", [20.0, 70.0])
def test_diffuse_plus_rough_metal_samples_themixture(theta):
    b = mixture([DIFFUSE, ROUGH_METAL], [0.3, 0.7])
    assert chi2_sampling_test(b, direction(theta), n=200_000, bins=16) > 1e-3
    assert weight_matches_eval(b, direction(theta)) < 1e-6


def test_mixture_albedo_is_the_weighted_sum():
    wo = direction(35.0)
    both = albedo(mixture([DIFFUSE, ROUGH_METAL], [0.3, 0.7]), wo, n=200_000)[0]
    alone = [albedo(mixture([m], [1.0]), wo, n=200_000)[0] for m in (DIFFUSE, ROUGH_METAL)]
    assert both == pytest.approx(0.3 * alone[0] + 0.7 * alone[1], rel=0.01)


def test_delta_closure_keeps_its_share():
    b = mixture([DIFFUSE, MIRROR], [0.5, 0.5])
    n = 100_000
    wo = direction(30.0)
    s = b.sample(np.repeat(wo[None], n, 0), np.full((n, 1), 550.0), np.random.default_rng(3).random((n, 3)),
                 np.zeros(n, int), np.zeros(n, bool))
    mirror = s.delta
    assert mirror.mean() == pytest.approx(0.5, abs=0.01)
    assert np.allclose(s.wi[mirror], wo * [-1, -1, 1])
    schlick = 1.0  # white F0: Schlick is 1 at every angle
    assert np.allclose(s.weight[mirror, 0], 0.5 * schlick / 0.5)
    assert s.weight[~mirror, 0].mean() == pytest.approx(0.8, rel=0.01)  # 0.5 x 0.8 / 0.5 on average
