"""Cycles' Filter Glossy (``stages.filter_glossy``): Cycles' rule for the alpha floor, the first surface never
blurred, and a point light's caustic through clear glass, which path tracing cannot find, blurred into view.
The absolute comparison with Cycles is ``tests/blender/test_filter_glossy.py``."""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
import pytest

from engine.tracer.bsdf.closure import (C_ALPHA, C_HAIR_M0, C_HAIR_MODEL, C_HAIR_S, C_HAIR_V, C_KIND, CLOSURE_ROW,
                                        CONDUCTOR, DIELECTRIC, DIFFUSE, HAIR, SHEEN)
from engine.tracer.bsdf.hair_kajiya import REFLECTION
from engine.tracer.path_tricks import LightPathTricks
from engine.tracer.pass_table import PassRequest
from engine.tracer.scene import Camera, Light, Material, World
from engine.tracer.stages.filter_glossy import blur_alpha, blur_glossy_closures
from tracer.test_path_tricks import _glass_ball_on_floor, _in_shadow, _render
from tracer.tracer_scenes import look_at, make_scene, quad

_Settings = namedtuple("_Settings", "filter_glossy")


@pytest.mark.parametrize("filter_glossy", [1.0, 0.5])
@pytest.mark.parametrize("min_pdf", [math.inf, 2.0, 1.0, 0.5, 0.19, 1e-3, 0.0])
def test_the_alpha_floor_is_cycles_rule(filter_glossy, min_pdf):
    """blur_pdf = min_pdf / F; below 1 the floor is sqrt(1 - blur_pdf) / 2 (Cycles' surface_shader.h)."""
    blur_pdf = min_pdf / filter_glossy
    expected = math.sqrt(1.0 - blur_pdf) * 0.5 if blur_pdf < 1.0 else 0.0
    assert blur_alpha(_Settings(1.0 / filter_glossy), min_pdf) == pytest.approx(expected, abs=1e-15)


def test_only_microfacet_lobes_are_raised_to_the_floor():
    rows = np.zeros((4, CLOSURE_ROW))
    rows[:, C_KIND] = (CONDUCTOR, DIELECTRIC, DIFFUSE, SHEEN)
    rows[:, C_ALPHA] = (0.0, 0.6, 0.0, 0.3)
    assert blur_glossy_closures(rows, 4, 0.4)
    assert list(rows[:, C_ALPHA]) == [0.4, 0.6, 0.0, 0.3]  # a rougher lobe keeps its own alpha
    rows[0, C_ALPHA] = 0.0
    assert not blur_glossy_closures(rows, 4, 1e-4)  # a floor below a mirror's threshold changes nothing
    assert rows[0, C_ALPHA] == 0.0


def test_a_chiang_fibre_takes_the_floor_on_its_variances_and_scale_and_the_hair_bsdf_none():
    """Cycles' ``bsdf_hair_chiang_blur``: v, s and the primary reflection's variance rise to the floor (the same
    number microfacets compare with their alpha); the Hair BSDF's lobes (``bsdf_hair.h``) have no blur."""
    rows = np.zeros((2, CLOSURE_ROW))
    rows[:, C_KIND] = HAIR
    rows[:, C_HAIR_MODEL] = (0.0, REFLECTION)
    rows[:, C_HAIR_V], rows[:, C_HAIR_S], rows[:, C_HAIR_M0] = (0.01, 0.01), (0.5, 0.02), (0.003, 0.003)
    blur_glossy_closures(rows, 2, 0.2)
    assert [rows[0, C_HAIR_V], rows[0, C_HAIR_S], rows[0, C_HAIR_M0]] == [0.2, 0.5, 0.2]
    assert [rows[1, C_HAIR_V], rows[1, C_HAIR_S], rows[1, C_HAIR_M0]] == [0.01, 0.02, 0.003]


def test_the_first_surface_is_never_blurred():
    """A mirror facing the camera reflects a lit grey wall behind the camera; with one bounce the only
    glossy vertex is the camera ray's own hit, so Filter Glossy changes no pixel."""
    mirror = quad((0, 2, 0), (1.5, 0, 0), (0, 0, 1.5))  # faces -y, toward the camera
    wall = quad((0, -2, 0), (0, 0, 3), (3, 0, 0))  # faces +y, toward the mirror
    materials = [Material("mirror", kind="conductor", base_color=(0.9, 0.9, 0.9), roughness=0.0),
                 Material("wall", base_color=(0.5, 0.5, 0.5))]
    camera = Camera("cam", look_at((0, 0, 0), (0, 1, 0)), (16, 16), film_width_mm=24.0, film_height_mm=24.0)
    scene = make_scene([(*mirror, 0), (*wall, 1)], materials, camera,
                       [Light("bulb", "point", np.array([0.0, -1.0, 0.0]), power_w=50.0)], World((0.0, 0.0, 0.0), 0.0))
    free, _, _ = _render(scene, samples=8, max_bounces=1)
    blurred, _, _ = _render(scene, LightPathTricks(filter_glossy=1.0), samples=8, max_bounces=1)
    assert free.mean() > 0.01
    assert np.array_equal(blurred, free)


def test_a_point_lights_caustic_through_glass_is_blurred_into_view():
    """A glass ball casts a point light's caustic on the floor. Path tracing alone cannot find it (floor →
    clear glass → a point): with light tracing off the shadow gets only the light the lit floor sends
    through the ball (measured 0.0049, against 0.41 on the lit floor). With Filter Glossy 1 the
    glass seen after the floor's diffuse bounce is rough GGX (alpha ≥ sqrt(1 - 1/π)/2 ≈ 0.41), light
    sampling reaches the light through it, and the shadow is lit by a blurred caustic; the lit floor keeps
    its direct light."""
    scene = _glass_ball_on_floor()
    light = scene.lights[0].position
    names = PassRequest(("Position", "Normal"))
    free, p, _ = _render(scene, samples=64, samples_per_pass=64, passes=names, light_tracing="off")
    blurred, _, r = _render(scene, LightPathTricks(filter_glossy=1.0), samples=64, samples_per_pass=64, passes=names)
    assert not r.tables.analysis.light_tracing  # a biased trick: caustics come from the blur, not light paths
    floor = np.all(np.abs(p["Normal"] - (0, 0, 1)) < 1e-9, -1) & (np.abs(p["Position"][..., 2]) < 1e-9)
    shadow = floor & _in_shadow(p["Position"], light, 0.05)
    lit = floor & ~_in_shadow(p["Position"], light, -0.05)
    print(f"MEASURED Filter Glossy shadow mean {blurred[shadow].mean():.4f} (off: {free[shadow].mean():.4f}), "
          f"lit floor {blurred[lit].mean():.4f} (off: {free[lit].mean():.4f})")
    assert shadow.sum() >= 10
    assert free[shadow].mean() < 0.02 * free[lit].mean()
    assert blurred[shadow].mean() > 10.0 * free[shadow].mean()  # measured 0.1835: 37 times
    assert blurred[lit].mean() == pytest.approx(free[lit].mean(), rel=0.05)
