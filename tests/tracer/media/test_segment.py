"""A ray segment through a homogeneous chromatic medium with equiangular sampling on (``media.segment``),
against closed forms: for every carried wavelength k, the weight of the paths that reach the surface at t
estimates T_k(t) = exp(-σ_t,k t), and that of the paths that scatter in a stretch [a, b) estimates
∫_a^b σ_s,k T_k(s) ds. The scene has a point light beside the ray (equiangular collisions) and a sun (a light
without a position: its picks sample a distance). Half the segments go toward a light, so the share of paths
that reach the surface is (1 - 0.7 / 2) × the average over wavelengths of exp(-σ_s,k t), 0.7 the selection
probability of the point light."""

from collections import namedtuple

import math

import numpy as np
import pytest

from engine.tracer.jit import kernel
from engine.tracer.lights.row import L_KIND, L_PX, L_PY, L_PZ, LIGHT_ROW, POINT, SUN
from engine.tracer.media.segment import cross_medium
from engine.tracer.media.spec import MediumSpec
from engine.tracer.media.table import build_media, coefficient_spectra
from engine.tracer.sampler import INDEPENDENT, SOBOL, pixel_seed
from engine.tracer.scene import Material
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID
from engine.tracer.state import COLLAPSED, new_path_state

from .segment_checks import assert_segment_estimates

WAVELENGTHS = np.array([450.0, 520.0, 600.0, 680.0])
T = 1.3
Settings = namedtuple("Settings", "sampler equiangular")
Lights = namedtuple("Lights", "rows select_prob select_cdf")


def _lights():
    rows = np.zeros((2, LIGHT_ROW))
    rows[0, L_KIND], rows[0, L_PX], rows[0, L_PY], rows[0, L_PZ] = POINT, 0.6, 0.95, 0.75  # 0.2 m off the ray
    rows[1, L_KIND] = SUN
    return Lights(rows, np.array([0.7, 0.3]), np.array([0.7, 1.0]))


@kernel
def _cross(state, media, spectra, settings, lights, collisions, sigma_t, sigma_s, f, p):
    for i in range(collisions.shape[0]):
        collisions[i] = cross_medium(state, i, T, media, spectra, settings, 0, sigma_t, sigma_s, lights, f, p)


def _segments(n, sampler, hero):
    spec = MediumSpec("haze", scatter=[(0.4, (0.9, 0.5, 0.2))], absorb=[(0.3, (0.3, 0.6, 0.9))])
    spectra = SpectrumTable()
    _, media, _, _ = build_media([Material("haze", kind="null", medium=spec)], {0}, spectra)
    sigma_s, sigma_a = coefficient_spectra(spec)
    at = np.searchsorted(np.asarray(VISIBLE_NM_GRID, float), WAVELENGTHS)
    k = len(WAVELENGTHS)
    state = new_path_state(n, k)
    state.medium[:], state.wavelength[:] = 0, WAVELENGTHS
    state.flags[:] = COLLAPSED if hero >= 0 else 0
    state.hero[:] = max(hero, 0)
    state.seed[:] = [pixel_seed(i % 64, 9) for i in range(n)]
    state.sample[:] = np.arange(n) // 64
    state.origin[:], state.direction[:], state.throughput[:] = (0.1, 0.75, 0.75), (1.0, 0.0, 0.0), 1.0
    state.radiance[:] = 0.0
    collisions = np.empty(n)
    _cross(state, media, spectra.arrays(), Settings(sampler, True), _lights(), collisions,
           *(np.empty(k) for _ in range(4)))
    assert np.all(state.radiance == 0.0)  # the medium does not emit
    return collisions, state.throughput.copy(), sigma_s[at], sigma_s[at] + sigma_a[at]


@pytest.mark.parametrize("sampler, hero", [(INDEPENDENT, -1), (SOBOL, -1), (INDEPENDENT, 1)])
def test_equiangular_segments_estimate_transmittance_and_collisions(sampler, hero):
    n = 64 * 1024
    collisions, weights, s_s, s_t = _segments(n, sampler, hero)
    carried = [hero] if hero >= 0 else list(range(len(WAVELENGTHS)))
    passed = np.isinf(collisions)
    assert np.all((collisions[~passed] >= 0.0) & (collisions[~passed] < T))
    stretches = ((0.0, 0.3), (0.3, 0.45), (0.45, 0.75), (0.75, T))  # the light is nearest the ray at 0.5 m
    assert_segment_estimates(collisions, weights, s_s, s_t, T, stretches, carried,
                             f"segment (sampler {sampler}, hero {hero})")
    # Distance sampling in half the segments and in the sun's picks of the other half (0.3 of it).
    share = (1.0 - 0.7 / 2) * np.exp(-s_s[carried] * T).mean()
    print(f"MEASURED share of paths reaching the surface: {passed.mean():.4f} (expected {share:.4f})")
    assert abs(passed.mean() - share) < 4.5 * math.sqrt(share * (1 - share) / n)
