"""Blender's Multiscatter GGX in the kernels (``C_MULTISCATTER``, ``materials.energy``): white furnaces of
every compensated lobe, the scale per wavelength of coloured ones, single scattering left as it was, and
the sampling (chi-square, weights against evaluate) of the compensated lobes."""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import (CONDUCTOR, DIELECTRIC, FRESNEL_CONDUCTOR, FRESNEL_DIELECTRIC, FRESNEL_F82,
                                        FRESNEL_NONE, GLASS, SAMPLED_TRANSMISSION)
from engine.tracer.bsdf.multiscatter import conductor_fss, energy_scale, load_energy_tables, reflection_albedo
from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
from engine.tracer.materials.table import MAT_MULTISCATTER
from engine.tracer.scene import Material
from engine.tracer.spectra.conductors import _lookup

from .bsdf_checks import MaterialBSDF, chi2_sampling_test, direction, weight_matches_eval

WHITE = Colour(rgb=(1.0, 1.0, 1.0))
ROUGHNESS = [0.0, 0.25, 0.5, 0.75, 1.0]
THETAS = [0.0, 45.0, 75.0]


def _bsdf(spec):
    return MaterialBSDF(Material("ms", shader=ShaderProgram([spec])))


def glossy(roughness, multiscatter=True, colour=WHITE):
    """Blender's Glossy BSDF: F = 1, the colour as the closure's tint and as its Fss."""
    return _bsdf(ClosureSpec(CONDUCTOR, tint=colour, alpha=roughness**2, fresnel=FRESNEL_NONE,
                             multiscatter=multiscatter, multiscatter_colour=colour if multiscatter else None))


def glass(roughness, multiscatter=True, ior=1.5):
    return _bsdf(ClosureSpec(DIELECTRIC, tint=WHITE, alpha=roughness**2, fresnel=GLASS, eta=ior,
                             multiscatter=multiscatter, multiscatter_colour=WHITE if multiscatter else None))


def _energy(bsdf, wo, n=200_000, lam=550.0, seed=3):
    """Mean sample weight as energy (a refraction's 1/η'² radiance factor taken out), per wavelength column."""
    rng = np.random.default_rng(seed)
    lam = np.broadcast_to(np.atleast_1d(lam), (n, np.size(lam))).copy()
    s = bsdf.sample(np.repeat(wo[None], n, 0), lam, rng.random((n, 3)), np.zeros(n, np.int64), np.zeros(n, bool))
    weight = np.where((s.flags & SAMPLED_TRANSMISSION != 0)[:, None], s.weight * s.eta_scale[:, None], s.weight)
    return weight.mean(0), weight.std(0) / np.sqrt(n)


def test_the_flag_marks_the_material():
    assert glossy(0.5).table.arrays.flags[0] & MAT_MULTISCATTER
    assert not glossy(0.5, multiscatter=False).table.arrays.flags[0] & MAT_MULTISCATTER
    assert not glossy(0.0).table.arrays.flags[0] & MAT_MULTISCATTER  # a mirror loses nothing


@pytest.mark.parametrize("roughness", ROUGHNESS)
def test_white_furnace_of_a_compensated_reflection(roughness):
    """F = 1: the compensated lobe reflects all it receives (within 1 %, never more), from any direction."""
    b = glossy(roughness)
    for theta in THETAS:
        energy, error = _energy(b, direction(theta))
        assert energy[0] == pytest.approx(1.0, abs=0.01), theta
        assert energy[0] < 1.0 + 0.002 + 4 * error[0], theta


@pytest.mark.parametrize("roughness", ROUGHNESS)
@pytest.mark.parametrize("below", [False, True])
def test_white_furnace_of_a_compensated_glass(roughness, below):
    """A lossless rough interface, reflection plus refraction, from outside and from inside."""
    b = glass(roughness)
    for theta in THETAS:
        energy, error = _energy(b, direction(theta, below=below))
        assert energy[0] == pytest.approx(1.0, abs=0.01), (theta, below)
        assert energy[0] < 1.0 + 0.002 + 4 * error[0], (theta, below)


@pytest.mark.parametrize("roughness", [0.5, 1.0])
def test_single_scatter_ggx_stays_as_it_was(roughness):
    """Without the flag the lobe keeps its single-scattering albedo E(μ) < 1 (the tables' value)."""
    b = glossy(roughness, multiscatter=False)
    tables = load_energy_tables()
    for theta in THETAS:
        energy, error = _energy(b, direction(theta))
        e, _ = reflection_albedo(tables, roughness, np.cos(np.radians(theta)))
        assert energy[0] == pytest.approx(e, abs=4 * error[0] + 2e-3), theta
        assert energy[0] < 0.98


def _ratio(compensated, single, wo, lam, n=4000):
    """Compensated over single-scattering sample weights for the same random numbers (a constant per column)."""
    rng = np.random.default_rng(4)
    u = rng.random((n, 3))
    lam_n = np.broadcast_to(lam, (n, len(lam))).copy()
    args = (np.repeat(wo[None], n, 0), lam_n, u, np.zeros(n, np.int64), np.zeros(n, bool))
    a, b = compensated.sample(*args), single.sample(*args)
    ok = (b.weight > 0).all(1)
    return a.weight[ok] / b.weight[ok]


def test_a_measured_metal_is_compensated_per_wavelength():
    """Gold's Fss follows its n + ik at each wavelength: more comes back in the red than in the blue."""
    lam = np.array([450.0, 550.0, 650.0])
    n_spec, k_spec = Colour(spectrum=("n", "Au")), Colour(spectrum=("k", "Au"))

    def gold(multiscatter):
        return _bsdf(ClosureSpec(CONDUCTOR, tint=WHITE, s0=n_spec, s1=k_spec, alpha=0.8**2, fresnel=FRESNEL_CONDUCTOR,
                                 multiscatter=multiscatter))

    wo = direction(30.0)
    ratio = _ratio(gold(True), gold(False), wo, lam)
    table_nm, n, k = _lookup("Au")
    e, e_avg = reflection_albedo(load_energy_tables(), 0.8, wo[2])
    expected = [energy_scale(conductor_fss(np.interp(x, table_nm, n), np.interp(x, table_nm, k)), e, e_avg)
                for x in lam]
    assert np.allclose(ratio, expected, rtol=2e-3)
    assert expected[2] > expected[0] > 1.0


def test_a_coloured_glossy_is_compensated_by_its_colour():
    """Cycles' Fss of a Glossy BSDF is its colour: a grey 0.5 lobe gets 1 + Fms(0.5) (1 - E)/E."""
    grey = Colour(rgb=(0.5, 0.5, 0.5))
    wo = direction(20.0)
    ratio = _ratio(glossy(0.9, colour=grey), glossy(0.9, multiscatter=False, colour=grey), wo, np.array([550.0]))
    e, e_avg = reflection_albedo(load_energy_tables(), 0.9, wo[2])
    assert np.allclose(ratio, energy_scale(0.5, e, e_avg), rtol=1e-3)


def _compensated_lobes():
    return {
        "glossy": glossy(0.6),
        "f82 metal": _bsdf(ClosureSpec(CONDUCTOR, tint=WHITE, s0=Colour(rgb=(0.95, 0.6, 0.3)),
                                       s1=Colour(rgb=(0.9, 0.9, 0.9)), alpha=0.5, fresnel=FRESNEL_F82,
                                       multiscatter=True)),
        "specular": _bsdf(ClosureSpec(CONDUCTOR, tint=WHITE, s0=WHITE, alpha=0.3, fresnel=FRESNEL_DIELECTRIC,
                                      eta=1.5, multiscatter=True)),
        "glass": glass(0.6),
    }


@pytest.mark.parametrize("name", ["glossy", "f82 metal", "specular", "glass"])
def test_compensated_lobes_sample_as_before(name):
    """A scale leaves the sampling alone: chi-square of the directions against evaluate's pdf, and the
    weights are f |cos| / pdf (the scale in both)."""
    b = _compensated_lobes()[name]
    for theta, below in ((30.0, False), (70.0, False)) + (((40.0, True),) if name == "glass" else ()):
        wo = direction(theta, below=below)
        assert chi2_sampling_test(b, wo, n=150_000, bins=16) > 1e-3, (name, theta)
        assert weight_matches_eval(b, wo) < 1e-6, (name, theta)
