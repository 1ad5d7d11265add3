"""Transparent bounces counted as Cycles counts them (``stages.bounces``): cut-outs (a Transparent BSDF) use up
Transparent Max Bounces, not Max Bounces; past its last bounce a path still goes through them; after its last
transparent bounce the next surface ends it; shadow rays cross as many. Closed forms: a stack of grey cut-outs in
front of an emitter or a point light passes τ^N of its light, and a floor lit by a uniform sky through a cut-out
shines ρ τ L."""

import numpy as np
import pytest

from engine.tracer.bsdf.closure import TRANSPARENT
from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec, World

from .tracer_scenes import look_at, make_scene, quad, settings

TINT = 0.8
LAYERS = 5


def _cut_out(name="cut-out", tint=TINT):
    return Material(name, shader=ShaderProgram([ClosureSpec(TRANSPARENT, tint=Colour(rgb=(tint,) * 3))]))


def _render(scene, **kw):
    with Renderer(scene, settings(**kw)) as r:
        r.render_pass()
        return r.image_rgb().astype(np.float64)


def _stack(layers):
    """An emitter at z = 0 seen from z = 10 through ``layers`` cut-outs at z = 1 .. layers."""
    cam = Camera("cam", look_at((0, 0, 10.0), (0, 0, 0), up=(0, 1, 0)), (8, 8), film_width_mm=6.0,
                 film_height_mm=6.0)
    lamp = Material("lamp", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    parts = [(*quad((0, 0, 0), (5, 0, 0), (0, 5, 0)), 0)]
    parts += [(*quad((0, 0, z), (5, 0, 0), (0, 5, 0)), 1) for z in range(1, layers + 1)]
    return make_scene(parts, [lamp, _cut_out()], cam, [], World(color=(0.0, 0.0, 0.0), strength=0.0))


@pytest.mark.parametrize("max_bounces", [0, 2])
def test_cut_outs_take_transparent_bounces_not_max_bounces(max_bounces):
    """Through five cut-outs of tint 0.8 the emitter keeps 0.8^5 of its light, even at Max Bounces 0 (each crossing
    is a transparent bounce). Exact: the only lobe goes straight through, with no roulette to play."""
    kw = dict(samples=1, samples_per_pass=1, max_bounces=max_bounces, russian_roulette_depth=64)
    bare = _render(_stack(0), **kw)
    through = _render(_stack(LAYERS), **kw)
    assert bare.mean() > 0.8 and bare.min() > 0.0  # one wavelength sample per pixel: colour noise, no black
    assert through / bare == pytest.approx(np.full_like(bare, TINT ** LAYERS), rel=1e-6)
    # absolute: an emitter of radiance 1 (white) behind the stack, averaged over the 64 pixels' wavelengths
    assert through.mean() == pytest.approx(TINT ** LAYERS, rel=0.03)


def test_after_its_last_transparent_bounce_a_path_ends_at_the_next_surface():
    """Cycles' PATH_RAY_TERMINATE_ON_NEXT_SURFACE, counted as Cycles 4.5 counts it (Transparent Max Bounces + 1
    crossings, as Max Bounces N allows N + 1 scatterings): with Transparent Max Bounces 4 the path crosses the five
    cut-outs and still sees the emitter's light (a surface's emission counts before it ends the path); with 3 the
    fifth cut-out ends it, black. Cycles 4.5 renders the same: tests/blender/test_transparent_bounces.py."""
    kw = dict(samples=1, samples_per_pass=1, max_bounces=0, russian_roulette_depth=64)
    bare = _render(_stack(0), **kw)
    five = _render(_stack(LAYERS), transparent_max_bounces=LAYERS - 1, **kw)
    four = _render(_stack(LAYERS), transparent_max_bounces=LAYERS - 2, **kw)
    assert five / bare == pytest.approx(np.full_like(bare, TINT ** LAYERS), rel=1e-6)
    assert np.all(four == 0.0)


def test_roulette_at_transparent_bounces_is_unbiased():
    """From the third transparent bounce on (Russian Roulette Depth 3) paths may end at a cut-out; the survivors
    carry the rest: the mean stays 0.8^5."""
    kw = dict(samples=64, samples_per_pass=64, max_bounces=0, russian_roulette_depth=3)
    through = _render(_stack(LAYERS), **kw).mean()
    ratio = through / _render(_stack(0), **kw).mean()
    print("MEASURED transmittance through 5 cut-outs with roulette:", ratio, "closed form", TINT ** LAYERS,
          "absolute:", through)
    assert ratio == pytest.approx(TINT ** LAYERS, rel=0.02)
    assert through == pytest.approx(TINT ** LAYERS, rel=0.03)  # absolute: the emitter's radiance is 1


def _floor_under_sky(cut_out):
    """A grey floor (albedo 0.5) seen from above under a uniform white sky of radiance 1, through a cut-out 1 m
    above it that covers all but 1e-4 of the floor's sky (200 m wide)."""
    cam = Camera("cam", look_at((0, 0, 0.5), (0, 0, 0), up=(0, 1, 0)), (16, 16), film_width_mm=10.0,
                 film_height_mm=10.0)
    floor = Material("floor", base_color=(0.5, 0.5, 0.5))
    parts = [(*quad((0, 0, 0), (0.5, 0, 0), (0, 0.5, 0)), 0)]
    if cut_out:
        parts.append((*quad((0, 0, 1.0), (100, 0, 0), (0, 100, 0)), 1))
    return make_scene(parts, [floor, _cut_out()], cam, [], World(color=(1.0, 1.0, 1.0), strength=1.0))


def test_past_max_bounces_a_path_still_goes_through_cut_outs():
    """Cycles' PATH_RAY_TERMINATE_AFTER_TRANSPARENT. At Max Bounces 0 the floor's light comes from its one vertex:
    light sampling (shadow rays cross the cut-out) and the BSDF ray, which meets the cut-out after the path's last
    bounce and must still reach the sky for its share of MIS. Radiance ρ τ L = 0.5 × 0.8 × 1; the camera sits
    under the cut-out, so it sees the floor directly."""
    kw = dict(samples=32, samples_per_pass=32, max_bounces=0)
    bare = _render(_floor_under_sky(False), **kw)
    through = _render(_floor_under_sky(True), **kw)
    ratio = through.mean() / bare.mean()
    print("MEASURED floor under a cut-out / bare:", ratio, "absolute:", through.mean(axis=(0, 1)))
    assert ratio == pytest.approx(TINT, rel=0.01)
    assert through.mean(axis=(0, 1)) == pytest.approx(np.full(3, 0.5 * TINT), rel=0.02)


def _floor_under_layers(layers):
    """A grey floor seen from 0.5 m above, under ``layers`` cut-outs at z = 1 .. layers and a point light at 12 m."""
    cam = Camera("cam", look_at((0, 0, 0.5), (0, 0, 0), up=(0, 1, 0)), (8, 8), film_width_mm=10.0,
                 film_height_mm=10.0)
    parts = [(*quad((0, 0, 0), (0.5, 0, 0), (0, 0.5, 0)), 0)]
    parts += [(*quad((0, 0, z), (5, 0, 0), (0, 5, 0)), 1) for z in range(1, layers + 1)]
    lamp = Light("lamp", "point", np.array([0.0, 0.0, 12.0]), power_w=1000.0)
    return make_scene(parts, [Material("floor", base_color=(0.5, 0.5, 0.5)), _cut_out()], cam, [lamp],
                      World(color=(0.0, 0.0, 0.0), strength=0.0))


def test_shadow_rays_cross_as_many_cut_outs_as_transparent_max_bounces():
    """Shadow rays cross Transparent Max Bounces cut-outs, as Cycles' do: ten cut-outs pass
    0.8^10 of the light with Transparent Max Bounces 10, and block it with the default 8. Exact: light sampling
    of a point light is the floor's only light at Max Bounces 0."""
    kw = dict(samples=1, samples_per_pass=1, max_bounces=0)
    bare = _render(_floor_under_layers(0), **kw)
    ten = _render(_floor_under_layers(10), transparent_max_bounces=10, **kw)
    eight = _render(_floor_under_layers(10), **kw)
    assert bare.mean() > 0.05
    assert ten / bare == pytest.approx(np.full_like(bare, TINT ** 10), rel=1e-6)
    # absolute: ρ/π · I / h² with I = 1000 W / 4π, h = 12 m, times 0.8^10
    assert ten.mean() == pytest.approx(0.5 / np.pi * 1000.0 / (4 * np.pi) / 12.0 ** 2 * TINT ** 10, rel=0.03)
    assert np.all(eight == 0.0)


def _floor_behind_cut_outs(seen_through, shadow_through):
    """A grey floor seen from 1 m through ``seen_through`` small cut-outs 0.3 m and more under the camera, lit by a
    point light 45° off its axis through ``shadow_through`` large cut-outs on the way to the light (which the
    camera's rays never meet, nor the shadow rays the camera's cut-outs). As ``tests/blender``'s scene."""
    cam = Camera("cam", look_at((0, 0, 1.0), (0, 0, 0), up=(0, 1, 0)), (8, 8), film_width_mm=10.0,
                 film_height_mm=10.0)
    parts = [(*quad((0, 0, 0), (0.5, 0, 0), (0, 0.5, 0)), 0)]
    parts += [(*quad((0, 0, 0.7 - 0.1 * k), (0.05, 0, 0), (0, 0.05, 0)), 1) for k in range(seen_through)]
    parts += [(*quad((z, 0, z), (1, 0, 0), (0, 1, 0)), 1) for z in range(2, 2 + shadow_through)]
    lamp = Light("lamp", "point", np.array([12.0, 0.0, 12.0]), power_w=1000.0)
    return make_scene(parts, [Material("floor", base_color=(0.5, 0.5, 0.5)), _cut_out()], cam, [lamp],
                      World(color=(0.0, 0.0, 0.0), strength=0.0))


def test_a_shadow_ray_crosses_what_its_path_left_of_transparent_max_bounces():
    """As Cycles (``integrate_shadow_max_transparent_hits``): a shadow ray from a vertex the path reached through k
    cut-outs crosses at most Transparent Max Bounces − k more, and the next blocks it. At Transparent Max Bounces
    4, the floor seen through 2 cut-outs is lit through 2 more at exactly 0.8² × 0.8² of the bare floor, and black
    behind 3; seen directly it is lit through 4. (Before, every shadow ray crossed 8 whatever the path had.)"""
    kw = dict(samples=1, samples_per_pass=1, max_bounces=0, transparent_max_bounces=4)
    bare = _render(_floor_behind_cut_outs(0, 0), **kw)
    # absolute: ρ/π · I cos θ / r², I = 1000 W / 4π, the light 12√2 m away at 45° (r² = 288 m²); within 3 % as
    # above (the default channels' white is (0.96, 1.01, 0.96) of it: measured 0.9762 of it in the mean, as at 0°)
    assert bare.mean() == pytest.approx(0.5 / np.pi * 1000.0 / (4 * np.pi) * np.cos(np.pi / 4) / 288.0, rel=0.03)
    assert _render(_floor_behind_cut_outs(2, 2), **kw) / bare == pytest.approx(np.full_like(bare, TINT ** 4),
                                                                                rel=1e-6)
    assert np.all(_render(_floor_behind_cut_outs(2, 3), **kw) == 0.0)
    assert _render(_floor_behind_cut_outs(0, 4), **kw) / bare == pytest.approx(np.full_like(bare, TINT ** 4),
                                                                                rel=1e-6)
    assert np.all(_render(_floor_behind_cut_outs(0, 5), **kw) == 0.0)
