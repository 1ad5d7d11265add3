"""Volume Scatter's phase functions besides Henyey-Greenstein (``phase_functions``) and their tables
(``tabulated_phase``): each density integrates to 1 over the sphere; Rayleigh's mean cos² θ is 2/5 (its closed
form); the table's CDF starts at 0, ends at 1 and rises; the value the kernel returns integrates to 1; and the
sampler draws directions with the exact phase function's density over coarse bins (chi-square) and reports
exactly the density it evaluates (weight 1)."""

import math

import numpy as np
import pytest
from scipy import stats

from engine.tracer.jit import kernel
from engine.tracer.media import phase_functions as pf
from engine.tracer.media.tabulated_phase import BINS, bin_edges, tabulated_sample, tabulated_value

LOBES = {
    "rayleigh": [(1.0, pf.RAYLEIGH, ())],
    "draine forward": [(1.0, pf.DRAINE, (0.6, 0.5))],
    "draine backward": [(1.0, pf.DRAINE, (-0.3, 2.0))],
    "fournier-forand seawater": [(1.0, pf.FOURNIER_FORAND, (0.018, 1.1))],
    "fournier-forand default": [(1.0, pf.FOURNIER_FORAND, (0.1, 1.33))],
    "mie haze 0.05 um": [(1.0, pf.MIE, (0.05,))],
    "mie 1 um": [(1.0, pf.MIE, (1.0,))],
    "mie 3 um": [(1.0, pf.MIE, (3.0,))],
    "mie fog 20 um": [(1.0, pf.MIE, (20.0,))],
    "hg + rayleigh mixture": [(0.3, pf.HENYEY_GREENSTEIN, (0.8,)), (0.7, pf.RAYLEIGH, ())],
}


def _sphere_integral(function, nodes=200_000):
    """2π ∫ f(cos θ) d cos θ, integrated in log(1 - cos θ) from 10⁻¹² to 2 (where forward peaks live)."""
    s = np.linspace(math.log(1e-12), math.log(2.0), nodes)
    t = np.exp(s)
    g = function(1.0 - t) * t
    return 2.0 * math.pi * np.sum(0.5 * (g[1:] + g[:-1]) * np.diff(s))


@pytest.mark.parametrize("name", LOBES)
def test_each_phase_function_integrates_to_one(name):
    assert _sphere_integral(lambda c: pf.mixture_density(c, LOBES[name])) == pytest.approx(1.0, abs=2e-3)


def test_rayleigh_has_its_closed_form_second_moment():
    moment = _sphere_integral(lambda c: c * c * pf.rayleigh(c))
    assert moment == pytest.approx(0.4, abs=1e-4)  # 3/(16π) 2π ∫ μ²(1 + μ²) dμ = 2/5


@pytest.mark.parametrize("name", LOBES)
def test_the_table_is_a_cdf_and_its_density_integrates_to_one(name):
    cdf = pf.phase_table(LOBES[name])
    assert cdf.shape == (BINS + 1,) and cdf[0] == 0.0 and cdf[-1] == 1.0 and np.all(np.diff(cdf) >= 0.0)
    table = cdf[None, :]
    edges = bin_edges()
    middles = 1.0 - 0.5 * (edges[1:] + edges[:-1])
    values = np.array([tabulated_value(table, 0, float(c)) for c in middles])
    total = 2.0 * math.pi * np.sum(values * np.diff(edges))
    assert total == pytest.approx(1.0, abs=1e-9)


@kernel
def _draw(table, d_in, n, seed, out_cos, out_pdf, out_value):
    np.random.seed(seed)
    for j in range(n):
        d, pdf = tabulated_sample(table, 0, d_in, np.random.random(), np.random.random())
        c = d[0] * d_in[0] + d[1] * d_in[1] + d[2] * d_in[2]
        out_cos[j] = c
        out_pdf[j] = pdf
        out_value[j] = tabulated_value(table, 0, c)


@pytest.mark.parametrize("name", LOBES)
def test_samples_follow_the_exact_phase_function_chi_square(name):
    lobes = LOBES[name]
    n = 200_000
    d_in = (0.3, -0.5, math.sqrt(1 - 0.34))
    cos, pdf, value = (np.empty(n) for _ in range(3))
    _draw(pf.phase_table(lobes)[None, :], d_in, n, 11, cos, pdf, value)
    np.testing.assert_allclose(pdf, value, rtol=1e-9)
    # 24 bins of 1 - cos θ, equiprobable under the exact phase function (found from its integral)
    s = np.linspace(math.log(1e-12), math.log(2.0), 400_001)
    t = np.exp(s)
    density = 2.0 * math.pi * pf.mixture_density(1.0 - t, lobes) * t
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(s))])
    cumulative /= cumulative[-1]
    edges = np.interp(np.linspace(0.0, 1.0, 25), cumulative, t)
    edges[0], edges[-1] = 0.0, 2.0
    counts, _ = np.histogram(1.0 - cos, bins=edges)
    expected = np.full(24, n / 24)
    assert stats.chisquare(counts, expected).pvalue > 1e-3


def test_mie_parameters_follow_the_published_fit():
    """Jendersie and d'Eon's fit: fog droplets scatter strongly forward, the HG lobe near 1."""
    g_hg, g_d, alpha, w = pf.mie_parameters(20.0)
    assert 0.99 < g_hg < 1.0 and 0.5 < g_d < 0.7 and 20.0 < alpha < 40.0 and 0.0 < w < 0.5
    g_hg, g_d, alpha, w = pf.mie_parameters(0.05)
    assert alpha == 250.0 and g_hg == pytest.approx(13.8 * 0.0025)
