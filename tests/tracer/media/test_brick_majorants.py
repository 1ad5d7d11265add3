"""Per-block majorants of grid media (``media.brick_majorants``) against brute force and closed forms:

- every block's majorant is the largest voxel its trilinear interpolation reads (brute force, odd grid sizes),
  and no point of the grid interpolates above its block's;
- through a sparse grid (a plume in empty air) along a slanted ray, ratio tracking's mean estimates
  exp(-σ_t(λ) ∫ D ds) per wavelength (the optical depth integrated on a fine grid), with blocks of 8 voxels and
  with one block for the whole grid (the grid's own majorant);
- delta tracking with spectral MIS through the same grid: the paths that pass estimate T_k(t) and those that
  scatter in a stretch [a, b) estimate ∫_a^b D σ_s,k T_k ds, per carried wavelength.

Each mean is checked within 4.5 standard errors of its own estimate (fixed seeds)."""

import math

import numpy as np
import pytest

from engine.tracer.media.brick_majorants import brick_entry, brick_majorant, brick_maxima
from engine.tracer.media.density_grid import DensityGrid, build_grids
from engine.tracer.media.grid_lookup import grid_density, index_ray
from engine.tracer.media.spec import MediumSpec
from engine.tracer.media.table import build_media, coefficient_spectra
from engine.tracer.sampler import INDEPENDENT, SOBOL, pixel_seed
from engine.tracer.scene import Material
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID
from engine.tracer.state import new_path_state

from .grid_walks import Settings, delta_track, ratio_estimates

VOXEL_M = 0.05
WAVELENGTHS = np.array([450.0, 520.0, 600.0, 680.0])
SCATTER = [(6.0, (0.9, 0.5, 0.2))]
ABSORB = [(2.0, (0.3, 0.6, 0.9))]


def _plume(shape=(40, 24, 24), seed=4):
    """Empty air with a lumpy plume (density 0.2-0.6) in a corner of the grid (about 2 % of the voxels)."""
    rng = np.random.default_rng(seed)
    x, y, z = np.meshgrid(*(np.arange(n) for n in shape), indexing="ij")
    inside = (x - 27.0) ** 2 / 36.0 + (y - 15.0) ** 2 / 16.0 + (z - 12.0) ** 2 / 25.0 < 1.0
    return np.where(inside, rng.uniform(0.2, 0.6, shape), 0.0).astype(np.float32)


def _brute_maxima(values, size):
    counts = [-(-(n + 1) // size) for n in values.shape]
    out = np.zeros(counts, np.float32)
    for i, j, k in np.ndindex(*counts):
        ranges = [slice(max(b * size - 1, 0), min((b + 1) * size, n)) for b, n in zip((i, j, k), values.shape)]
        block = values[tuple(ranges)]
        out[i, j, k] = block.max() if block.size else 0.0
    return out


@pytest.mark.parametrize("size", [4, 8])
def test_each_blocks_majorant_bounds_what_it_interpolates(size):
    rng = np.random.default_rng(1)
    values = np.where(rng.random((13, 7, 18)) < 0.2, rng.uniform(0.0, 5.0, (13, 7, 18)), 0.0).astype(np.float32)
    np.testing.assert_array_equal(brick_maxima(values, size), _brute_maxima(values, size))
    grids = build_grids([DensityGrid(values, np.eye(4))], brick_voxels=size)
    for p in rng.uniform(-1.0, np.array(values.shape), (4000, 3)):
        point = (float(p[0]), float(p[1]), float(p[2]))
        block, _, _, _ = brick_entry(grids, 0, point, (1.0, 1.0, 1.0), 0.0)
        assert grid_density(grids, 0, point) <= brick_majorant(grids, 0, block) * (1 + 1e-6)
    # one voxel reaches the blocks whose interpolation reads it: voxel 4b - 1 (b > 0) is shared by blocks b - 1
    # and b, every other voxel belongs to one block per axis
    single = np.zeros((13, 7, 18), np.float32)
    single[size - 1, 3, 16] = 2.0
    shared_y = 2 if 3 % size == size - 1 else 1
    assert np.count_nonzero(brick_maxima(single, size)) == 2 * shared_y * (2 if 16 % size == size - 1 else 1)


def _media(values, brick_voxels=None):
    """(MediaArrays, SpectrumArrays, σ_s, σ_t at ``WAVELENGTHS`` at density 1) for a grid of ``values``
    (voxels of ``VOXEL_M``, index i at world x = ``VOXEL_M`` i); ``brick_voxels`` past the grid's size: one
    block, the grid's own majorant."""
    grid = DensityGrid(np.asarray(values, np.float32), np.diag([VOXEL_M, VOXEL_M, VOXEL_M, 1.0]))
    spec = MediumSpec("plume", scatter=SCATTER, absorb=ABSORB, density_grid=grid)
    spectra = SpectrumTable()
    _, media, _, _ = build_media([Material("plume", kind="null", medium=spec)], {0}, spectra)
    if brick_voxels is not None:
        media = media._replace(grids=build_grids([grid], brick_voxels=brick_voxels))
    sigma_s, sigma_a = coefficient_spectra(spec)
    at = np.searchsorted(np.asarray(VISIBLE_NM_GRID, float), WAVELENGTHS)
    return media, spectra.arrays(), sigma_s[at], sigma_s[at] + sigma_a[at]


def _optical_depth(media, o, d, lengths, steps=20000):
    """∫_0^L D ds along o + s d for each L of ``lengths`` (trilinear density summed on a fine grid)."""
    o2, d2 = index_ray(media.grids, 0, o, d)
    s = (np.arange(steps) + 0.5) / steps * max(lengths)
    density = np.array([grid_density(media.grids, 0, tuple(np.asarray(o2) + x * np.asarray(d2))) for x in s])
    cumulative = np.concatenate([[0.0], np.cumsum(density) * (s[1] - s[0])])
    return np.interp(lengths, np.concatenate([[0.0], s + 0.5 * (s[1] - s[0])]), cumulative), s, density


RAY_O, RAY_D = (0.0, 0.1, 0.05), tuple(np.array([1.35, 0.65, 0.55]) / np.linalg.norm([1.35, 0.65, 0.55]))
RAY_T = 2.0  # across the plume (s from about 1.3 to 1.9 m) and a little past it


@pytest.mark.parametrize("brick_voxels", [None, 1000])
def test_ratio_tracking_through_a_sparse_plume_is_beer_lambert(brick_voxels):
    media, spectra, _, sigma_t = _media(_plume(), brick_voxels)
    n = 40000
    out = np.empty((n, len(WAVELENGTHS)))
    ratio_estimates(media, spectra, WAVELENGTHS, RAY_O, RAY_D, RAY_T, out, np.empty(len(WAVELENGTHS)))
    tau = _optical_depth(media, RAY_O, RAY_D, [RAY_T])[0][0]
    expected = np.exp(-sigma_t * tau)
    mean, stderr = out.mean(0), out.std(0) / math.sqrt(n)
    print(f"MEASURED ratio tracking, plume, blocks {brick_voxels or 8}: estimate / exp(-sigma_t tau)",
          np.round(mean / expected, 4).tolist(), "expected", np.round(expected, 4).tolist())
    assert 0.05 < expected.min() and expected.max() < 0.95  # the ray crosses the plume
    assert np.all(np.abs(mean - expected) < 4.5 * stderr)


@pytest.mark.parametrize("sampler", [INDEPENDENT, SOBOL])
def test_delta_tracking_through_a_sparse_plume_estimates_transmittance_and_collisions(sampler):
    media, spectra, sigma_s, sigma_t = _media(_plume())
    n, k = 64 * 1024, len(WAVELENGTHS)
    state = new_path_state(n, k)
    state.medium[:], state.wavelength[:], state.flags[:], state.hero[:] = 0, WAVELENGTHS, 0, 0
    state.seed[:] = [pixel_seed(i % 64, 5) for i in range(n)]
    state.sample[:] = np.arange(n) // 64
    state.origin[:], state.direction[:], state.throughput[:] = RAY_O, RAY_D, 1.0
    collisions = np.empty(n)
    delta_track(state, media, spectra, Settings(sampler), RAY_T, collisions, *(np.empty(k) for _ in range(4)))
    weights = state.throughput
    _, s, density = _optical_depth(media, RAY_O, RAY_D, [RAY_T])
    ds = s[1] - s[0]
    tau = np.cumsum(density) * ds - 0.5 * density * ds  # optical depth (density) to each fine step's middle
    transmittance = np.exp(-np.outer(tau, sigma_t))
    checks = [(np.isinf(collisions), np.exp(-sigma_t * (tau[-1] + 0.5 * density[-1] * ds)), "passes")]
    for a, b in ((0.0, 1.2), (1.2, 1.6), (1.6, RAY_T)):
        inside = (s >= a) & (s < b)
        expected = (density[inside, None] * sigma_s * transmittance[inside]).sum(0) * ds
        checks.append(((collisions >= a) & (collisions < b), expected, f"scatters in [{a}, {b})"))
    for chosen, expected, what in checks:
        estimate = np.where(chosen[:, None], weights, 0.0)
        mean, stderr = estimate.mean(0), estimate.std(0) / math.sqrt(n)
        print(f"MEASURED delta tracking, plume, sampler {sampler}, {what}: estimate / closed form",
              np.round(mean / np.maximum(expected, 1e-300), 4).tolist())
        assert np.all(np.abs(mean - expected) <= 4.5 * stderr + 1e-4 * expected)
