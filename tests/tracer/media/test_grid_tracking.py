"""Grid media (``media.delta_tracking``, ``media.ratio_tracking``) against closed forms, one ray at a time:

- ratio tracking through a constant grid estimates exp(-D σ_t(λ) d) per wavelength (Beer-Lambert) and,
  through a grid that is empty on one half and D on the other, exp(-D σ_t(λ) L / 2) along a ray of length L
  across both;
- delta tracking with spectral MIS through a chromatic grid (a ray from a fixed point): the throughput of the
  paths that pass estimates T_k(t) = exp(-D σ_t,k t), and that of the paths that scatter in a stretch
  [a, b) estimates ∫_a^b D σ_s,k T_k(s) ds, for every carried wavelength k, also for a collapsed path
  (its hero alone);
- an absurdly dense grid (free flights of 1e-26 m) ends every walk within ``density_grid.MAX_TRACKING_STEPS``.

Each mean is checked within 4.5 standard errors of its own estimate (fixed seeds)."""

import math

import numpy as np
import pytest

from engine.tracer.media.density_grid import DensityGrid
from engine.tracer.media.spec import MediumSpec
from engine.tracer.media.table import build_media, coefficient_spectra
from engine.tracer.sampler import INDEPENDENT, SOBOL, pixel_seed
from engine.tracer.scene import Material
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID
from engine.tracer.state import COLLAPSED, new_path_state

from .grid_walks import Settings, delta_track, ratio_estimates
from .segment_checks import assert_segment_estimates

VOXEL_M = 0.1
WAVELENGTHS = np.array([450.0, 520.0, 600.0, 680.0])
SCATTER = [(3.0, (0.9, 0.5, 0.2))]
ABSORB = [(1.0, (0.3, 0.6, 0.9))]


def _media(values):
    """(MediaArrays, SpectrumArrays, σ_s, σ_t at ``WAVELENGTHS`` at density 1) for a grid of ``values`` with
    voxels of ``VOXEL_M`` (index i at world x = 0.1 i)."""
    grid = DensityGrid(np.asarray(values, np.float32), np.diag([VOXEL_M, VOXEL_M, VOXEL_M, 1.0]))
    spec = MediumSpec("grid", scatter=SCATTER, absorb=ABSORB, density_grid=grid)
    spectra = SpectrumTable()
    _, media, _, _ = build_media([Material("grid", kind="null", medium=spec)], {0}, spectra)
    sigma_s, sigma_a = coefficient_spectra(spec)
    at = np.searchsorted(np.asarray(VISIBLE_NM_GRID, float), WAVELENGTHS)
    return media, spectra.arrays(), sigma_s[at], sigma_s[at] + sigma_a[at]


def _ratio_mean(values, o, d, distance, n=40000):
    media, spectra, _, sigma_t = _media(values)
    out = np.empty((n, len(WAVELENGTHS)))
    ratio_estimates(media, spectra, WAVELENGTHS, o, d, distance, out, np.empty(len(WAVELENGTHS)))
    return out.mean(0), out.std(0) / math.sqrt(n), sigma_t


def test_ratio_tracking_through_a_constant_grid_is_beer_lambert_per_wavelength():
    density, distance = 1.5, 1.3  # the ray stays inside the constant voxels (index 1 .. 14)
    mean, stderr, sigma_t = _ratio_mean(np.full((16, 16, 16), density), (0.1, 0.75, 0.75), (1.0, 0.0, 0.0), distance)
    expected = np.exp(-density * sigma_t * distance)
    print("MEASURED ratio tracking / exp(-sigma_t d), constant grid:", np.round(mean / expected, 4).tolist(),
          "stderr / expected:", np.round(stderr / expected, 4).tolist(), "expected:", np.round(expected, 4).tolist())
    assert expected.max() / expected.min() > 1.5  # chromatic: the wavelengths differ
    assert np.all(np.abs(mean - expected) < 4.5 * stderr)


def test_ratio_tracking_across_an_empty_half_and_a_dense_half():
    density = 2.0
    values = np.zeros((16, 16, 16))
    values[8:] = density
    # From index 0 to 15 along x (L = 1.5 m): the density is 0 up to voxel 7, rises linearly to voxel 8 and is
    # D from there, so its integral is D (1/2 + 7) voxels = D L / 2.
    length = 15 * VOXEL_M
    mean, stderr, sigma_t = _ratio_mean(values, (0.0, 0.75, 0.75), (1.0, 0.0, 0.0), length)
    expected = np.exp(-density * sigma_t * length / 2)
    print("MEASURED ratio tracking / exp(-sigma_t D L/2), half-empty grid:", np.round(mean / expected, 4).tolist())
    assert np.all(np.abs(mean - expected) < 4.5 * stderr)


def test_a_ray_that_misses_the_grid_is_not_attenuated():
    mean, _, _ = _ratio_mean(np.full((4, 4, 4), 5.0), (0.0, 2.0, 0.0), (1.0, 0.0, 0.0), 3.0, n=10)
    assert np.all(mean == 1.0)


def _delta_tracking(n, sampler, collapsed_hero=-1, values=None):
    density, t = 1.5, 1.3
    media, spectra, sigma_s, sigma_t = _media(np.full((16, 16, 16), density) if values is None else values)
    k = len(WAVELENGTHS)
    state = new_path_state(n, k)
    state.medium[:] = 0
    state.wavelength[:] = WAVELENGTHS
    state.flags[:] = COLLAPSED if collapsed_hero >= 0 else 0
    state.hero[:] = max(collapsed_hero, 0)
    state.seed[:] = [pixel_seed(i % 64, 5) for i in range(n)]
    state.sample[:] = np.arange(n) // 64
    state.origin[:] = (0.1, 0.75, 0.75)
    state.direction[:] = (1.0, 0.0, 0.0)
    state.throughput[:] = 1.0
    collisions = np.empty(n)
    delta_track(state, media, spectra, Settings(sampler), t, collisions, *(np.empty(k) for _ in range(4)))
    return collisions, state.throughput.copy(), density * sigma_s, density * sigma_t, t


@pytest.mark.parametrize("sampler, hero", [(INDEPENDENT, -1), (SOBOL, -1), (INDEPENDENT, 2)])
def test_delta_tracking_with_spectral_mis_estimates_transmittance_and_collisions(sampler, hero):
    n = 64 * 1024
    collisions, weights, s_s, s_t, t = _delta_tracking(n, sampler, hero)
    carried = [hero] if hero >= 0 else range(len(WAVELENGTHS))
    passed = np.isinf(collisions)
    assert np.all(collisions[~passed] < t) and np.all(collisions[~passed] > 0.0)
    assert_segment_estimates(collisions, weights, s_s, s_t, t, ((0.0, 0.3), (0.3, 0.7), (0.7, t)), carried,
                             f"delta tracking (sampler {sampler}, hero {hero})")


def test_a_white_scatterer_weighs_every_path_exactly_one():
    spec_scatter = [(2.0, (1.0, 1.0, 1.0))]
    grid = DensityGrid(np.random.default_rng(3).random((8, 8, 8)).astype(np.float32), np.diag([0.2, 0.2, 0.2, 1.0]))
    spectra = SpectrumTable()
    _, media, _, _ = build_media([Material("w", kind="null", medium=MediumSpec("w", scatter=spec_scatter,
                                                                              density_grid=grid))], {0}, spectra)
    k, n = len(WAVELENGTHS), 2000
    state = new_path_state(n, k)
    state.medium[:], state.wavelength[:], state.flags[:], state.hero[:] = 0, WAVELENGTHS, 0, 0
    state.seed[:], state.sample[:] = [pixel_seed(i, 2) for i in range(n)], 0
    state.origin[:], state.direction[:], state.throughput[:] = (0.1, 0.7, 0.7), (1.0, 0.0, 0.0), 1.0
    collisions = np.empty(n)
    delta_track(state, media, spectra.arrays(), Settings(INDEPENDENT), 1.3, collisions,
                 *(np.empty(k) for _ in range(4)))
    assert np.isfinite(collisions).any() and np.isinf(collisions).any()
    assert np.allclose(state.throughput, 1.0, rtol=1e-12)


def _absurdly_dense_half():
    """A grid empty up to x = 0.7 m and of density 1e25 beyond: free flights of ~1e-26 m, so a walk from x = 0
    would take ~1e25 steps to reach the dense half without the bound."""
    values = np.zeros((16, 16, 16), np.float32)
    values[8:] = 1e25
    return values


def test_an_absurdly_dense_grid_ends_every_walk_within_the_bound():
    # Shadow rays across the dense half: the transmittance is exp(-1e25), 0 in any float.
    mean, _, _ = _ratio_mean(_absurdly_dense_half(), (0.0, 0.75, 0.75), (1.0, 0.0, 0.0), 1.5, n=2)
    assert np.all(mean == 0.0)
    # Paths from the empty half: each walk ends (the test returns), its path with a weight of 0 (counted as
    # opaque) or scattered in the dense half, never a NaN or an infinite weight.
    collisions, weights, _, _, _ = _delta_tracking(2, INDEPENDENT, values=_absurdly_dense_half())
    ended = np.all(weights == 0.0, axis=1)
    assert np.all(np.isfinite(weights)) and np.all(weights >= 0.0)
    assert np.all(ended | ((collisions >= 0.7) & (collisions < 1.3)))
    print("MEASURED absurdly dense grid: walks ended as opaque", int(ended.sum()), "of", len(ended))


def test_homogeneous_media_have_no_grid():
    _, media, _, _ = build_media([Material("fog", kind="null", medium=MediumSpec("fog", scatter=SCATTER))], {0},
                              SpectrumTable())
    assert media.grid.tolist() == [-1]
