"""Emission of grid media (``media.grid_emission``, ``media.temperature_emission``) against closed forms, one
ray at a time through delta tracking, the radiance it gathers per carried wavelength k:

- a grid of constant density D that emits ε(λ) (Emission Strength × Color) everywhere:
  ε_k (1 - exp(-D σ_t,k t)) / (D σ_t,k), for every wavelength and for a collapsed path (its hero alone);
- an empty grid (density 0) that emits: ε_k t, gathered only through the emission's null rate;
- a temperature grid rising linearly from 1000 K to 2000 K along the ray inside a constant density, as
  Cycles' Temperature Attribute: ∫ exp(-D σ_t,k s) ε_k(T(s)) ds with Cycles' blackbody intensity
  σ_SB 10⁻⁶ / π T⁴ of the luminance-1 Planck spectrum, by quadrature (the rows interpolated by the kernel
  are tested through it);
- an Emission Strength grid rising linearly along the ray (``MediumSpec.emission_field``): the constant
  emission plus the strength times the field's emission, by quadrature.

Each mean is checked within 4.5 standard errors of its own estimate (fixed seeds)."""

from collections import namedtuple

import math

import numpy as np
import pytest

from engine.tracer.jit import kernel
from engine.tracer.media.delta_tracking import track_grid_medium
from engine.tracer.media.density_grid import DensityGrid
from engine.tracer.media.spec import MediumSpec
from engine.tracer.media.table import build_media, coefficient_spectra, emission_on_grid
from engine.tracer.media.temperature_emission import blackbody_intensity
from engine.tracer.spectra.tinted_blackbody import tinted_blackbody
from engine.tracer.sampler import INDEPENDENT, SOBOL, pixel_seed
from engine.tracer.scene import Material
from engine.tracer.spectra.table import SpectrumTable
from engine.tracer.spectra.wavelengths import VISIBLE_NM_GRID
from engine.tracer.state import COLLAPSED, new_path_state

VOXEL_M = 0.1
WAVELENGTHS = np.array([450.0, 520.0, 600.0, 680.0])
AT = np.searchsorted(np.asarray(VISIBLE_NM_GRID, float), WAVELENGTHS)
SCATTER = [(3.0, (0.9, 0.5, 0.2))]
ABSORB = [(1.0, (0.3, 0.6, 0.9))]
GLOW = [(2.0, (1.0, 0.4, 0.1), None)]
ORIGIN, LENGTH = (0.1, 0.75, 0.75), 1.3  # along +x, inside the 16³ grid's constant voxels
Settings = namedtuple("Settings", "sampler")


@kernel
def _walk(state, media, spectra, settings, t, sigma_t, sigma_s, f, p):
    for i in range(state.medium.shape[0]):
        track_grid_medium(state, i, t, media, spectra, settings, 0, sigma_t, sigma_s, f, p)


def _grid(values):
    return DensityGrid(np.asarray(values, np.float32), np.diag([VOXEL_M, VOXEL_M, VOXEL_M, 1.0]))


def _gathered(spec, n, sampler=INDEPENDENT, hero=-1):
    """(mean radiance [K], its standard error [K]) of ``n`` walks along the test ray through ``spec``."""
    spectra = SpectrumTable()
    _, media, _, _ = build_media([Material("m", kind="null", medium=spec)], {0}, spectra)
    k = len(WAVELENGTHS)
    state = new_path_state(n, k)
    state.medium[:], state.wavelength[:], state.hero[:] = 0, WAVELENGTHS, max(hero, 0)
    state.flags[:] = COLLAPSED if hero >= 0 else 0
    state.seed[:] = [pixel_seed(i % 64, 11) for i in range(n)]
    state.sample[:] = np.arange(n) // 64
    state.origin[:], state.direction[:], state.throughput[:], state.radiance[:] = ORIGIN, (1.0, 0.0, 0.0), 1.0, 0.0
    _walk(state, media, spectra.arrays(), Settings(sampler), LENGTH, *(np.empty(k) for _ in range(4)))
    return state.radiance.mean(0), state.radiance.std(0) / math.sqrt(n)


def _assert_close(mean, stderr, expected, carried, label):
    print(f"MEASURED {label}: gathered / closed form", np.round(mean[carried] / expected[carried], 4).tolist(),
          "stderr / closed form", np.round(stderr[carried] / expected[carried], 4).tolist())
    assert np.all(expected[carried] > 0.0)
    assert np.all(np.abs(mean - expected)[carried] < 4.5 * stderr[carried])


def _extinction(density):
    spec = MediumSpec("c", scatter=SCATTER, absorb=ABSORB)
    sigma_s, sigma_a = coefficient_spectra(spec)
    return density * (sigma_s + sigma_a)[AT]


@pytest.mark.parametrize("sampler, hero", [(INDEPENDENT, -1), (SOBOL, -1), (INDEPENDENT, 1)])
def test_a_constant_grid_glows_as_beer_lambert_integrates(sampler, hero):
    density = 1.5
    spec = MediumSpec("glow", scatter=SCATTER, absorb=ABSORB, emission=GLOW,
                      density_grid=_grid(np.full((16, 16, 16), density)))
    mean, stderr = _gathered(spec, 32 * 1024, sampler, hero)
    s_t = _extinction(density)
    emitted = emission_on_grid(spec)[AT]
    expected = emitted * -np.expm1(-s_t * LENGTH) / s_t
    carried = [hero] if hero >= 0 else list(range(len(WAVELENGTHS)))
    _assert_close(mean, stderr, expected, carried, f"constant glowing grid (sampler {sampler}, hero {hero})")
    if hero >= 0:
        assert np.all(np.delete(mean, hero) == 0.0)  # a collapsed path gathers its hero's light alone


def test_an_empty_grid_glows_along_its_whole_length():
    spec = MediumSpec("glow", emission=GLOW, density_grid=_grid(np.zeros((16, 16, 16))))
    mean, stderr = _gathered(spec, 16 * 1024)
    expected = emission_on_grid(spec)[AT] * LENGTH
    _assert_close(mean, stderr, expected, list(range(len(WAVELENGTHS))), "empty glowing grid")


def test_a_temperature_grid_glows_at_its_blackbody_temperature_point_by_point():
    density, base_k = 0.8, 1000.0
    rise = np.broadcast_to((1.0 + np.arange(16) / 15.0)[:, None, None], (16, 16, 16))  # T 1000 K → 2000 K
    spec = MediumSpec("fire", scatter=SCATTER, absorb=ABSORB, density_grid=_grid(np.full((16, 16, 16), density)),
                      blackbody=[(1.0, 1.0, base_k, (1.0, 0.9, 0.8))], temperature_grid=_grid(rise))
    mean, stderr = _gathered(spec, 32 * 1024)
    s = (np.arange(4000) + 0.5) * LENGTH / 4000  # midpoint quadrature along the ray
    temperature = base_k * (1.0 + (ORIGIN[0] + s) / VOXEL_M / 15.0)
    glow = blackbody_intensity(temperature, 1.0)[:, None] * tinted_blackbody(temperature, (1.0, 0.9, 0.8))[:, AT]
    expected = (np.exp(-s[:, None] * _extinction(density)[None, :]) * glow).sum(0) * LENGTH / 4000
    _assert_close(mean, stderr, expected, list(range(len(WAVELENGTHS))), "temperature grid 1000-2000 K")


def test_a_strength_grid_glows_in_proportion_to_it_point_by_point():
    """An Emission Strength baked to a grid rising linearly 0.5 → 2 along the ray (``emission_field``), beside a
    constant Emission Strength term, inside a constant density: ∫ exp(-D σ_t,k s) (ε_const + S(s) ε_unit) ds."""
    density = 0.8
    rise = np.broadcast_to((0.5 + 1.5 * np.arange(16) / 15.0)[:, None, None], (16, 16, 16))
    field = [(1.5, (0.2, 0.5, 1.0))]
    spec = MediumSpec("glow", scatter=SCATTER, absorb=ABSORB, emission=GLOW, emission_field=field,
                      density_grid=_grid(np.full((16, 16, 16), density)), strength_grid=_grid(rise))
    mean, stderr = _gathered(spec, 32 * 1024)
    s = (np.arange(4000) + 0.5) * LENGTH / 4000
    strength = 0.5 + 1.5 * (ORIGIN[0] + s) / VOXEL_M / 15.0
    unit = emission_on_grid(MediumSpec("unit", emission=[(w, rgb, None) for w, rgb in field]))[AT]
    glow = emission_on_grid(MediumSpec("constant", emission=GLOW))[AT][None, :] + strength[:, None] * unit[None, :]
    expected = (np.exp(-s[:, None] * _extinction(density)[None, :]) * glow).sum(0) * LENGTH / 4000
    _assert_close(mean, stderr, expected, list(range(len(WAVELENGTHS))), "strength grid 0.5-2")


def test_grid_media_that_do_not_emit_take_no_emission_rate():
    spec = MediumSpec("smoke", scatter=SCATTER, density_grid=_grid(np.ones((4, 4, 4))))
    _, media, _, _ = build_media([Material("m", kind="null", medium=spec)], {0}, SpectrumTable())
    assert media.emission.tolist() == [-1] and media.emission_rate.tolist() == [0.0]
    glowing = MediumSpec("glow", emission=GLOW, density_grid=_grid(np.ones((4, 4, 4))))
    _, media, _, _ = build_media([Material("m", kind="null", medium=glowing)], {0}, SpectrumTable())
    assert media.emission_rate.tolist() == [pytest.approx(1.0 / VOXEL_M)]
