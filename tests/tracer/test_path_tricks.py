"""Cycles' Light Paths tricks (``path_tricks``): Clamp Direct / Indirect and the caustics toggles."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.pass_table import PassRequest
from engine.tracer.path_tricks import LightPathTricks
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from tracer.tracer_scenes import look_at, make_scene, quad, settings, uv_sphere
from tracer.test_passes import _facing_wall


def _render(scene, tricks=None, **kw):
    with Renderer(scene, settings(light_path_tricks=tricks or LightPathTricks(), **kw)) as r:
        while not r.finished:
            r.render_pass()
        return r.image_rgb().astype(np.float64), {k: v.astype(np.float64) for k, v in r.pass_images().items()}, r


def test_clamp_direct_bounds_each_sample_of_a_bright_light():
    """A wall lit by a point light at the camera, nothing else: all its light is direct (light sampled at
    the first surface; the BSDF rays escape to a black world). Clamp Direct c bounds each sample's
    |R| + |G| + |B| by 3c, so a pixel's too; Clamp Indirect changes nothing here."""
    scene = _facing_wall()
    free, _, _ = _render(scene, samples=16)
    c = 0.25 * free.sum(-1).min() / 3.0  # a quarter of the dimmest pixel: every sample is clamped
    clamped, _, _ = _render(scene, LightPathTricks(clamp_direct=c), samples=16)
    assert free.sum(-1).min() > 3.9 * 3 * c
    assert np.all(clamped.sum(-1) <= 3 * c * (1 + 1e-6))
    # Each sample is at the limit in |R| + |G| + |B|; a saturated colour's single-wavelength samples have
    # negative Rec.709 components, so R + G + B of their mean is a little lower (measured 1.3 % at most).
    assert np.all(clamped.sum(-1) > 0.97 * 3 * c)
    indirect_only, _, _ = _render(scene, LightPathTricks(clamp_indirect=1e-6), samples=16)
    assert np.array_equal(indirect_only, free)


def test_clamp_indirect_bounds_light_after_the_first_bounce():
    """Inside a closed grey room lit by a point light, Clamp Indirect c leaves the direct light and
    bounds what every later contribution adds: the image lies between the direct-only image and it
    plus 3c per later vertex (max bounces 2: at most 2 more contributions by light sampling and 2 by hits)."""
    camera = Camera("cam", look_at((0, -0.9, 0), (0, 1, 0)), (12, 12), film_width_mm=36.0, film_height_mm=36.0)
    room = [(*quad(c, u, v), 0) for c, u, v in (((0, 1, 0), (1, 0, 0), (0, 0, 1)), ((0, -1, 0), (0, 0, 1), (1, 0, 0)),
                                               ((1, 0, 0), (0, 0, 1), (0, 1, 0)), ((-1, 0, 0), (0, 1, 0), (0, 0, 1)),
                                               ((0, 0, 1), (0, 1, 0), (1, 0, 0)), ((0, 0, -1), (1, 0, 0), (0, 1, 0)))]
    scene = make_scene(room, [Material("grey", base_color=(0.7, 0.7, 0.7))], camera,
                       [Light("bulb", "point", np.array([0.3, 0.2, 0.5]), power_w=50.0)])
    direct, _, _ = _render(scene, samples=16, max_bounces=0)
    free, _, _ = _render(scene, samples=16, max_bounces=2)
    c = 0.01
    clamped, _, _ = _render(scene, LightPathTricks(clamp_indirect=c), samples=16, max_bounces=2)
    assert (free - direct).sum(-1).mean() > 4 * 3 * c  # the indirect light is well above the limit
    assert np.all(clamped.sum(-1) >= direct.sum(-1) - 1e-9)
    assert np.all(clamped.sum(-1) <= direct.sum(-1) + 4 * 3 * c + 1e-9)


def _glass_ball_on_floor():
    """A glass ball (r 0.5 m) on a grey floor, a point light to its right, a black world, seen from the
    front left so the floor in its shadow (and the caustic there) is in view."""
    floor = quad((0, 0, 0), (3, 0, 0), (0, 3, 0))
    ball = uv_sphere((0, 0, 0.5), 0.5, rings=32, segments=64)
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)), Material("glass", kind="dielectric", glass="N-BK7")]
    light = Light("bulb", "point", np.array([2.0, 0.0, 2.0]), power_w=400.0)
    camera = Camera("cam", look_at((-0.8, -3.0, 2.5), (-0.7, 0.0, 0.0)), (32, 24), film_width_mm=36.0,
                    film_height_mm=27.0)
    return make_scene([(*floor, 0), (*ball, 1)], materials, camera, [light], World((0.0, 0.0, 0.0), 0.0))


def _in_shadow(points, light, margin):
    """Floor points whose segment to ``light`` passes the ball's centre closer than its radius - margin."""
    centre = np.array([0.0, 0.0, 0.5])
    d = light - points
    t = np.clip(((centre - points) * d).sum(-1) / (d * d).sum(-1), 0.0, 1.0)
    closest = points + t[..., None] * d
    return np.linalg.norm(closest - centre, axis=-1) < 0.5 - margin


def test_caustics_off_leave_the_shadow_of_a_glass_ball_black():
    """Refractive and Reflective caustics off: after the floor's diffuse bounce the glass is left out, so
    no light reaches the floor in the ball's shadow (0 exactly, black world); on, the caustic is there.
    The lit floor keeps its closed form, ρ/π · (P/4π) cos θ / r², either way."""
    scene = _glass_ball_on_floor()
    light = scene.lights[0].position
    names = PassRequest(("Position", "Normal"))
    on, p, r_on = _render(scene, samples=64, samples_per_pass=64, passes=names)
    off, _, r_off = _render(scene, LightPathTricks(caustics_reflective=False, caustics_refractive=False), samples=64,
                            samples_per_pass=64, passes=names)
    assert r_on.tables.analysis.light_tracing and not r_off.tables.analysis.light_tracing
    floor = np.all(np.abs(p["Normal"] - (0, 0, 1)) < 1e-9, -1) & (np.abs(p["Position"][..., 2]) < 1e-9)
    shadow = floor & _in_shadow(p["Position"], light, 0.05)
    lit = floor & ~_in_shadow(p["Position"], light, -0.05)
    assert shadow.sum() >= 10 and lit.sum() >= 100
    assert np.all(off[shadow] == 0.0)
    assert on[shadow].mean() > 0.05 * on[lit].mean()  # the caustic
    to_light = light - p["Position"]
    r2 = (to_light ** 2).sum(-1)
    expected = 0.8 / np.pi * 400.0 / (4 * np.pi) * to_light[..., 2] / np.sqrt(r2) / r2
    ratio = off[lit].mean(-1) / expected[lit]
    assert abs(ratio.mean() - 1.0) < 0.03, ratio.mean()


@pytest.mark.parametrize("field", ["clamp_direct", "clamp_indirect", "filter_glossy"])
def test_negative_or_infinite_tricks_are_refused(field):
    for bad in (-1.0, float("inf"), float("nan")):
        with pytest.raises(PrismInputError, match="Light Paths"):
            LightPathTricks(**{field: bad}).validate()
