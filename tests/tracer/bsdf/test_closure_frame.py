"""A closure with a normal of its own (Coat Normal, mixed shaders with different Normal inputs) scatters in
its own frame: its f × cosine is the closure's about that normal, sampling matches the mixture's pdf
(chi-square), and a rotated lobe reflects what the unrotated one does seen from the rotated direction."""

import math

import numpy as np
import pytest

from engine.tracer.bsdf.closure import C_FRAME_X, C_FRAME_Y, C_FRAME_Z, C_FRAMED
from engine.tracer.scene import Material

from .bsdf_checks import albedo, chi2_sampling_test, direction, mixture, weight_matches_eval

DIFFUSE = Material("white", base_color=(0.8, 0.8, 0.8))
ROUGH_METAL = Material("metal", kind="conductor", base_color=(1.0, 1.0, 1.0), roughness=0.4)
TILT = np.array([math.sin(math.radians(40.0)), 0.0, math.cos(math.radians(40.0))])  # 40° towards +x


def _material(materials, weights, framed):
    """One material of ``materials`` with ``weights``; closure ``framed`` (an index or None) shades with
    ``TILT`` as its own normal."""

    def tilt(closures):
        if framed is not None:
            closures[framed, C_FRAMED] = 1.0
            closures[framed, [C_FRAME_X, C_FRAME_Y, C_FRAME_Z]] = TILT

    return mixture(materials, weights, tilt)


def test_tilted_diffuse_is_lambert_about_its_own_normal():
    b = _material([DIFFUSE], [1.0], framed=0)
    rng = np.random.default_rng(5)
    wi = rng.normal(size=(4000, 3))
    wi /= np.linalg.norm(wi, axis=1, keepdims=True)
    wo = np.repeat(direction(30.0, phi_deg=0.0)[None], len(wi), 0)
    f, pdf = b.eval(wo, wi, np.full((len(wi), 1), 550.0))
    cos_own = wi @ TILT
    expected = np.where(cos_own > 0.0, 0.8 * cos_own / math.pi, 0.0)  # f × |cos_material| = ρ/π cos_own
    got = f[:, 0] * np.abs(wi[:, 2])
    assert np.abs(got - expected).max() < 2e-3  # 0.8 is upsampled to a smooth spectrum: ~0.1 % at 550 nm
    assert np.allclose(pdf, np.maximum(cos_own, 0.0) / math.pi, atol=1e-12)


@pytest.mark.parametrize("theta", [20.0, 60.0])
def test_mixture_with_a_tilted_lobe_samples_its_pdf(theta):
    b = _material([DIFFUSE, ROUGH_METAL], [0.4, 0.6], framed=1)
    assert chi2_sampling_test(b, direction(theta), n=200_000, bins=16) > 1e-3
    assert weight_matches_eval(b, direction(theta)) < 1e-6


def test_rotated_lobe_reflects_what_it_reflects_about_its_own_normal():
    wo = direction(30.0, phi_deg=0.0)
    tilted = albedo(_material([ROUGH_METAL], [1.0], framed=0), wo, n=200_000)[0]
    s = np.cross([0.0, 0.0, 1.0], TILT)
    s /= np.linalg.norm(s)
    # wo seen from the tilted normal: its angle to TILT (both in the x-z plane)
    theta_own = math.degrees(math.acos(float(wo @ TILT)))
    plain = albedo(_material([ROUGH_METAL], [1.0], framed=None), direction(theta_own, phi_deg=0.0), n=200_000)[0]
    assert tilted == pytest.approx(plain, rel=0.01)


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


@pytest.mark.parametrize("view_deg, tilt_deg", [(80.0, 30.0), (60.0, 50.0), (85.0, 10.0)])
def test_bump_map_correction_lifts_the_reflection_just_above_the_surface(view_deg, tilt_deg):
    """Cycles' ensure_valid_specular_reflection: a normal tilted away from a grazing view whose mirror reflection
    would leave below the surface is raised, in the plane of the normal and ng, until the reflection's height
    is min(0.9 cos, 0.01); a normal whose reflection already leaves above is kept."""
    from engine.tracer.materials.closure_normals import valid_specular_normal

    ng = (0.0, 0.0, 1.0)
    view = tuple(_unit([math.sin(math.radians(view_deg)), 0.0, math.cos(math.radians(view_deg))]))
    tilted = tuple(_unit([-math.sin(math.radians(tilt_deg)), 0.0, math.cos(math.radians(tilt_deg))]))
    n = np.array(valid_specular_normal(ng, view, tilted))
    reflection = 2.0 * (n @ view) * n - view
    assert np.linalg.norm(n) == pytest.approx(1.0, abs=1e-12) and abs(n[1]) < 1e-12
    assert reflection[2] == pytest.approx(min(0.9 * view[2], 0.01), abs=1e-9)
    kept = tuple(_unit([math.sin(math.radians(5.0)), 0.0, math.cos(math.radians(5.0))]))
    assert valid_specular_normal(ng, view, kept) == kept


def test_bump_shadowing_drops_light_from_behind_the_smooth_surface():
    """A diffuse closure whose bumped normal leans 40° from the smooth normal: light that reaches its side of
    the bumped normal from below the smooth surface carries nothing; light from above is softened by the GGX
    shadowing of alpha² = (1/cos²40° - 1) / 8 at the light's angle to the smooth normal (Cycles'
    bump_shadowing_term with Bump Map Correction)."""
    from engine.tracer.bsdf.closure import C_BUMPED, C_KIND, C_SMOOTH_X, C_SMOOTH_Y, C_SMOOTH_Z, DIFFUSE
    from engine.tracer.bsdf.closure_frame import BUMP_SOFTENED, bump_shadowing

    row = np.zeros(40)
    row[C_KIND] = DIFFUSE
    row[C_BUMPED] = BUMP_SOFTENED
    smooth = -TILT * [1.0, 1.0, -1.0]  # the smooth normal, 40° the other way from the closure's (z)
    row[[C_SMOOTH_X, C_SMOOTH_Y, C_SMOOTH_Z]] = smooth
    below = tuple(_unit([1.0, 0.0, 0.3]))  # above the closure's normal, below the smooth surface
    assert below @ smooth < 0.0 < below[2]
    assert bump_shadowing(row, below, True) == 0.0 and bump_shadowing(row, below, False) == 0.0
    above = tuple(_unit([-0.3, 0.2, 1.0]))
    cos_i = float(np.dot(above, smooth))
    alpha2 = (1.0 / math.cos(math.radians(40.0)) ** 2 - 1.0) / 8.0
    tan2 = 1.0 / cos_i ** 2 - 1.0
    assert bump_shadowing(row, above, True) == pytest.approx(1.0 / (1.0 + 0.5 * (math.sqrt(1.0 + alpha2 * tan2) - 1.0)))
    row[C_BUMPED] = 1.0  # Bump Map Correction off: the test alone
    assert bump_shadowing(row, above, True) == 1.0 and bump_shadowing(row, below, True) == 0.0
