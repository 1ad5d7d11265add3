"""Subsurface scattering's pieces against closed forms: the entry bounce's directions (Snell's law through a
smooth surface; chi-square against the GGX refraction density, and Skin's half-cosine mixture), the closure's
zero evaluation, and the walk's coefficients (albedo 1 scatters without loss, Cycles' floor on α)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numba
import numpy as np

from engine.tracer.bsdf.closure import (C_ALPHA, C_ETA, C_SSS_METHOD, CLOSURE_ROW, SSS_SKIN,
                                        SUBSURFACE)
from engine.tracer.bsdf.microfacet import visible_normal_pdf
from engine.tracer.bsdf.subsurface_entry import entry_direction
from engine.tracer.subsurface.coefficients import (MAX_ALPHA, MIN_ALPHA, legacy_alpha, skin_radius_factor,
                                                   van_de_hulst_alpha, walk_coefficients)

from .bsdf.bsdf_checks import chi2_sampling_test, direction


def _row(alpha, ior, skin=False):
    row = np.zeros(CLOSURE_ROW)
    row[0] = SUBSURFACE
    row[C_ALPHA], row[C_ETA] = alpha, ior
    row[C_SSS_METHOD] = SSS_SKIN if skin else 0.0
    return row


@numba.njit
def _sample(row, wo, u, wi, ok):
    for i in range(wo.shape[0]):
        d, valid = entry_direction(row, (wo[i, 0], wo[i, 1], wo[i, 2]), u[i, 0], u[i, 1], u[i, 2])
        wi[i, 0], wi[i, 1], wi[i, 2] = d
        ok[i] = valid


@numba.njit
def _refraction_pdf(wo, wi, alpha, eta):
    """Density of wi refracted from wo through GGX visible normals (index 1 → eta)."""
    h = (-(wo[0] + eta * wi[0]), -(wo[1] + eta * wi[1]), -(wo[2] + eta * wi[2]))
    length = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])
    if length == 0.0:
        return 0.0
    h = (h[0] / length, h[1] / length, h[2] / length)
    if h[2] < 0.0:
        h = (-h[0], -h[1], -h[2])
    o = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]
    i = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]
    if o <= 0.0 or i >= 0.0:
        return 0.0
    return visible_normal_pdf(wo, h, alpha) * eta * eta * abs(i) / (o + eta * i) ** 2


@numba.njit
def _pdf(wo, wi, alpha, eta, skin, out):
    for n in range(wo.shape[0]):
        a = (wo[n, 0], wo[n, 1], wo[n, 2])
        b = (wi[n, 0], wi[n, 1], wi[n, 2])
        if skin:
            out[n] = 0.5 * max(-b[2], 0.0) / math.pi + 0.5 * _refraction_pdf(a, b, 1.0, eta)
        else:
            out[n] = _refraction_pdf(a, b, alpha, eta)


class _Entry:
    """The entry bounce as ``bsdf_checks`` reads a BSDF: samples, and their density."""

    def __init__(self, alpha, ior, skin=False):
        self.row, self.alpha, self.ior, self.skin = _row(alpha, ior, skin), alpha, ior, skin

    def sample(self, wo, lam, u, hero, collapsed):
        wi = np.zeros_like(wo)
        ok = np.zeros(len(wo), dtype=np.bool_)
        _sample(self.row, wo, u, wi, ok)
        return SimpleNamespace(wi=wi, pdf=ok.astype(float), weight=ok[:, None].astype(float))

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        pdf = np.zeros(len(wo))
        _pdf(np.ascontiguousarray(wo), np.ascontiguousarray(wi), self.alpha, self.ior, self.skin, pdf)
        return None, pdf


def test_a_smooth_entry_refracts_by_snells_law():
    row = _row(1e-6, 1.5)
    for theta in (0.0, 0.4, 1.2):
        wo = (math.sin(theta), 0.0, math.cos(theta))
        wi, valid = entry_direction(row, wo, 0.3, 0.4, 0.6)
        assert valid and wi[2] < 0.0
        assert abs(math.hypot(wi[0], wi[1]) - math.sin(theta) / 1.5) < 1e-3
        assert wi[0] * wo[0] <= 0.0  # on through, not back


def test_rough_entries_follow_the_ggx_refraction_density():
    for alpha, ior, theta in ((0.25, 1.4, 30.0), (0.6, 1.33, 65.0)):
        p = chi2_sampling_test(_Entry(alpha, ior), direction(theta), n=200_000, bins=16)
        assert p > 1e-3, (alpha, ior, theta, p)


def test_skin_entries_are_half_cosine_half_rough_refraction():
    p = chi2_sampling_test(_Entry(0.1, 1.4, skin=True), direction(40.0), n=200_000, bins=16)
    assert p > 1e-3, p


def test_every_entry_goes_into_the_surface():
    rng = np.random.default_rng(3)
    for skin in (False, True):
        wo = np.repeat(np.array([direction(80.0)]), 20_000, 0)
        wi, ok = np.zeros_like(wo), np.zeros(len(wo), np.bool_)
        _sample(_row(0.9, 3.8, skin), wo, rng.random((len(wo), 3)), wi, ok)
        assert ok.all() and (wi[:, 2] < 0.0).all()
        assert np.allclose(np.linalg.norm(wi, axis=1), 1.0, atol=1e-9)


def test_the_subsurface_closure_evaluates_to_nothing():
    from engine.tracer.bsdf.dispatch import closure_evaluate, closure_is_delta

    row = _row(0.3, 1.4)
    f = np.ones(4)
    pdf = closure_evaluate(row, np.ones((3, 4)), 1.4, tuple(direction(20.0)), tuple(direction(50.0, below=True)),
                           np.full(4, 550.0), 0, False, f)
    assert pdf == 0.0 and not f.any() and closure_is_delta(row)


def test_walk_coefficients():
    # albedo 1 scatters (almost) without loss; albedo 0 absorbs at once; both fits agree at g = 0
    assert van_de_hulst_alpha(1.0, 0.0) == MAX_ALPHA and van_de_hulst_alpha(0.0, 0.0) < 1e-5
    albedos = np.linspace(0.05, 0.95, 19)
    alphas = [van_de_hulst_alpha(a, 0.0) for a in albedos]
    assert np.all(np.diff(alphas) > 0)
    assert max(abs(van_de_hulst_alpha(a, 0.0) - legacy_alpha(a, 0.0)) for a in albedos) < 0.01
    # forward scattering needs a larger single-scattering albedo for the same look
    assert van_de_hulst_alpha(0.5, 0.8) > van_de_hulst_alpha(0.5, 0.0)
    sigma_t, alpha, factor = walk_coefficients(0.8, 0.01, 0.0, False, 1.4)
    assert sigma_t == 100.0 and factor == 1.0 and alpha == van_de_hulst_alpha(0.8, 0.0)
    sigma_t, alpha, factor = walk_coefficients(0.01, 0.01, 0.0, False, 1.4)  # Cycles' floor on α
    assert alpha == MIN_ALPHA and abs(factor - van_de_hulst_alpha(0.01, 0.0) / MIN_ALPHA) < 1e-12
    # Skin: the radius shrinks by sqrt(3 (1 - α')), α' the dipole albedo: white is almost no radius
    assert skin_radius_factor(0.0, 1.4) == math.sqrt(3.0)
    assert skin_radius_factor(1.0, 1.4) < 2e-3 and 0.05 < skin_radius_factor(0.5, 1.4) < math.sqrt(3.0)


def _subsurface_sphere(albedo, radius_m):
    from engine.tracer.bsdf.closure import SSS_RANDOM_WALK
    from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
    from engine.tracer.scene import Material

    from .tracer_scenes import sphere_under_sky

    colour = Colour(rgb=(albedo,) * 3)
    spec = ClosureSpec(SUBSURFACE, tint=colour, s0=colour, s1=Colour(rgb=(1.0, 1.0, 1.0)), alpha=1.0, eta=1.4,
                       subsurface=(radius_m, 0.0, SSS_RANDOM_WALK))
    scene = sphere_under_sky(size=12)
    scene.materials = [Material("skin", shader=ShaderProgram([spec]))]
    return scene


def test_a_white_walk_at_max_bounces_0_returns_everything():
    """The walk is no bounce (Cycles counts none): at Max Bounces 0 the exit still sees the sky, so a lossless
    sphere in a white furnace renders as the sky. (Before, the exit had no bounce left: skin spheres at Max
    Bounces 0 rendered black, tests/blender/test_subsurface.py.)"""
    from engine.tracer.renderer import Renderer

    from .tracer_scenes import settings

    s = settings(samples=16, samples_per_pass=16, max_bounces=0)
    with Renderer(_subsurface_sphere(1.0, 0.3), s) as r:
        r.render_pass()
        image = r.image_rgb().astype(np.float64)
    centre = image[4:8, 4:8].mean((0, 1))  # the sphere's middle in the 12 x 12 frame
    print("MEASURED white walk at Max Bounces 0, centre / sky:", centre)
    assert np.all(np.abs(centre - 1.0) < 0.02), centre


def test_a_white_walk_in_a_furnace_returns_everything_and_turns_light_tracing_off():
    from engine.tracer.renderer import Renderer

    from .tracer_scenes import settings

    s = settings(samples=16, samples_per_pass=16, max_bounces=8, light_tracing="on")
    scene = _subsurface_sphere(1.0, 0.3)
    with Renderer(scene, s) as r:
        assert not r.tables.analysis.light_tracing
        assert "subsurface scattering" in r.tables.analysis.light_tracing_note
        r.render_pass()
        image = r.image_rgb().astype(np.float64).mean((0, 1))
        assert r.stats["nan_samples"] == 0
    scene.triangles = scene.triangles[:0]
    scene.triangle_material = scene.triangle_material[:0]
    with Renderer(scene, s) as sky_renderer:
        sky_renderer.render_pass()
        sky = sky_renderer.image_rgb().astype(np.float64).mean((0, 1))
    print("MEASURED white walk in the furnace / sky:", image / sky)
    assert np.all(np.abs(image / sky - 1.0) < 0.01), image / sky
