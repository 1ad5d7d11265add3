"""Cycles' per-kind bounce limits (Light Paths ▸ Max Bounces ▸ Diffuse, Glossy, Transmission, Volume;
``path_tricks.LightPathTricks``, ``stages.bounces.bounces_left``), against a closed form: inside a closed sphere
whose wall emits L_e and reflects diffusely with albedo ρ, a path that may make D diffuse reflections sees
L_e (1 + ρ + ... + ρ^(D+1)): the last reflection's light comes from the vertex after it (Cycles' kernel limit is
the setting + 1, as Max Bounces' is). Limits of the other kinds leave such a sphere alone."""

import numpy as np
import pytest

from engine.tracer.path_tricks import LightPathTricks
from engine.tracer.renderer import Renderer

from .tracer_scenes import inside_glowing_sphere, settings

ALBEDO = 0.5
MAX_BOUNCES = 12


def _mean(tricks, samples=16):
    kw = dict(samples=samples, samples_per_pass=samples, max_bounces=MAX_BOUNCES, russian_roulette_depth=64,
              light_path_tricks=tricks)
    with Renderer(inside_glowing_sphere(size=8, albedo=ALBEDO), settings(**kw)) as r:
        r.render_pass()
        return float(r.image_rgb().astype(np.float64).mean())


def _series(reflections):
    return sum(ALBEDO ** k for k in range(reflections + 2))


@pytest.mark.parametrize("diffuse", [0, 1, 3])
def test_a_diffuse_limit_keeps_that_many_reflections(diffuse):
    measured = _mean(LightPathTricks(diffuse_bounces=diffuse))
    print(f"MEASURED Diffuse {diffuse}: {measured:.5f}, closed form {_series(diffuse):.5f}")
    assert measured == pytest.approx(_series(diffuse), rel=0.01)


def test_limits_of_other_kinds_leave_diffuse_light_alone():
    """Glossy, Transmission and Volume 0 count no diffuse reflection: the sphere renders as with Max Bounces
    alone, L_e (1 + ρ + ... + ρ^(12+1)); the same sphere with Diffuse 0 gives 1 + ρ, so the two are told apart."""
    others = _mean(LightPathTricks(glossy_bounces=0, transmission_bounces=0, volume_bounces=0))
    print(f"MEASURED Glossy/Transmission/Volume 0: {others:.5f}, closed form {_series(MAX_BOUNCES):.5f}")
    assert others == pytest.approx(_series(MAX_BOUNCES), rel=0.01)


def test_limits_at_or_above_max_bounces_change_nothing():
    tricks = LightPathTricks(diffuse_bounces=MAX_BOUNCES, glossy_bounces=64)
    assert not tricks.limits_kinds(MAX_BOUNCES)
    assert tricks.bounce_limits(MAX_BOUNCES) == (MAX_BOUNCES,) * 4
    assert LightPathTricks(volume_bounces=0).limits_kinds(MAX_BOUNCES)


def test_a_negative_limit_is_refused():
    from engine.tracer.errors import PrismInputError

    with pytest.raises(PrismInputError, match="Max Bounces ▸ Glossy -1 is negative"):
        LightPathTricks(glossy_bounces=-1).validate()


def test_light_tracing_stays_off_while_a_limit_binds():
    """Light paths would have to count a camera path's bounces from its far end: path tracing renders the caustics
    (and says why); a limit at Max Bounces lets light tracing back on."""
    from benchmarks.scenes import build
    from engine.tracer.scene import Light

    scene = build("cornell_glass", (8, 8))
    scene.lights = [Light("bulb", "point", np.array([0.0, 0.0, 1.9]), power_w=20.0)]  # small: light-traced
    assert Renderer(scene, settings()).tables.analysis.light_tracing
    limited = Renderer(scene, settings(light_path_tricks=LightPathTricks(transmission_bounces=2)))
    assert not limited.tables.analysis.light_tracing
    assert "caustics by path tracing (bounce limits per kind)" in limited.strategy
    at_max = settings(light_path_tricks=LightPathTricks(transmission_bounces=8), max_bounces=8)
    assert Renderer(scene, at_max).tables.analysis.light_tracing
