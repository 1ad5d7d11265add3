"""Transparent bounces as Cycles 4.5 counts them, both engines rendering one .blend in the test: five planes with
a Transparent BSDF (Color 0.8) over an emitter of strength 1, seen from above at Max Bounces 0. Each crossing is
a transparent bounce, not a bounce: the emitter shows 0.8^5 of its radiance in both. Cycles 4.5 lets a path make
Transparent Max Bounces + 1 of them: at 4 the emitter still shows, at 3 the fifth plane ends the path in both."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, camera, material, node, plane

TINT, LAYERS = 0.8, 5


def _stack():
    black_world()
    lamp, nodes, link = material("Lamp")
    link(node(nodes, "ShaderNodeEmission", Strength=1.0).outputs[0], nodes["Output"].inputs["Surface"])
    plane("Emitter", 10.0, mat=lamp)
    cut_out, nodes, link = material("Cut-out")
    link(node(nodes, "ShaderNodeBsdfTransparent", Color=(TINT,) * 3).outputs[0], nodes["Output"].inputs["Surface"])
    for z in range(1, LAYERS + 1):
        plane(f"Layer {z}", 10.0, location=(0.0, 0.0, float(z)), mat=cut_out)
    camera((0.0, 0.0, 10.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(8, 8))


def _both(scene, transparent_max_bounces):
    scene.prism.max_bounces, scene.prism.transparent_max_bounces = 0, transparent_max_bounces
    scene.prism.russian_roulette_depth = 64  # exact: no roulette at the crossings, in either engine
    scene.cycles.min_transparent_bounces = 64
    cycles = render_cycles_rgba(scene, 4, max_bounces=0, transparent_max_bounces=transparent_max_bounces)
    prism = render_prism_rgba(scene, 4)
    return prism[..., :3].astype(np.float64), cycles[..., :3].astype(np.float64)


def test_cut_outs_are_transparent_bounces_as_in_cycles(prism_addon, fresh_scene):
    _stack()
    prism, cycles = _both(fresh_scene, 8)
    print(f"MEASURED five cut-outs at Max Bounces 0: Prism {prism.mean():.5f}, Cycles {cycles.mean():.5f}, "
          f"closed form {TINT ** LAYERS:.5f}")
    assert cycles.mean() == pytest.approx(TINT ** LAYERS, rel=0.005)
    assert prism.mean(axis=(0, 1)) == pytest.approx(np.full(3, TINT ** LAYERS), rel=0.02)
    assert prism.mean() / cycles.mean() == pytest.approx(1.0, abs=0.02)


def test_the_last_transparent_bounce_ends_the_path_at_the_next_surface_as_in_cycles(prism_addon, fresh_scene):
    _stack()
    prism, cycles = _both(fresh_scene, LAYERS - 1)
    print(f"MEASURED five cut-outs, Transparent Max Bounces 4: Prism {prism.mean():.5f}, Cycles {cycles.mean():.5f}")
    assert cycles.mean() == pytest.approx(TINT ** LAYERS, rel=0.005)
    assert prism.mean(axis=(0, 1)) == pytest.approx(np.full(3, TINT ** LAYERS), rel=0.02)
    assert prism.mean() / cycles.mean() == pytest.approx(1.0, abs=0.02)
    prism, cycles = _both(fresh_scene, LAYERS - 2)
    print(f"MEASURED five cut-outs, Transparent Max Bounces 3: Prism {prism.mean():.5f}, Cycles {cycles.mean():.5f}")
    assert cycles.max() < 1e-6
    assert np.all(prism == 0.0)


def _floor_behind_cut_outs(seen_through, shadow_through):
    """A grey floor seen from 1 m through ``seen_through`` small cut-outs 0.3 m and more under the camera (beyond its
    Clip Start), lit by a point
    light 45° off the camera's axis through ``shadow_through`` large cut-outs on the way to it (camera rays never
    meet these, nor shadow rays the camera's)."""
    black_world()
    floor, nodes, link = material("Floor")
    link(node(nodes, "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)).outputs[0], nodes["Output"].inputs["Surface"])
    plane("Floor", 1.0, mat=floor)
    cut_out, nodes, link = material("Cut-out")
    link(node(nodes, "ShaderNodeBsdfTransparent", Color=(TINT,) * 3).outputs[0], nodes["Output"].inputs["Surface"])
    for k in range(seen_through):
        plane(f"Near {k}", 0.1, location=(0.0, 0.0, 0.7 - 0.1 * k), mat=cut_out)
    for z in range(2, 2 + shadow_through):
        plane(f"Far {z}", 2.0, location=(float(z), 0.0, float(z)), mat=cut_out)
    lamp = bpy.data.objects.new("Lamp", bpy.data.lights.new("Lamp", "POINT"))
    lamp.data.energy, lamp.data.shadow_soft_size = 1000.0, 0.0
    lamp.location = (12.0, 0.0, 12.0)
    bpy.context.scene.collection.objects.link(lamp)
    camera((0.0, 0.0, 1.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(8, 8), sensor_mm=10.0)


@pytest.mark.parametrize("shadow_through", [2, 3])
def test_a_shadow_ray_crosses_what_its_path_left_as_in_cycles(prism_addon, fresh_scene, shadow_through):
    """At Transparent Max Bounces 4, a floor seen through 2 cut-outs: its shadow rays may cross 4 − 2 more (Cycles'
    ``integrate_shadow_max_transparent_hits``). Through 2 it is lit at 0.8⁴ of the bare floor in both engines;
    behind 3 it is black in both (before 2026-12-07, Prism lit it through up to 8)."""
    _floor_behind_cut_outs(0, 0)
    bare, bare_cycles = _both(fresh_scene, 4)
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    _floor_behind_cut_outs(2, shadow_through)
    prism, cycles = _both(bpy.context.scene, 4)
    print(f"MEASURED floor through 2 cut-outs, shadow rays through {shadow_through}: Prism {prism.mean():.5f}, "
          f"Cycles {cycles.mean():.5f}; bare floor Prism {bare.mean():.5f}, Cycles {bare_cycles.mean():.5f}")
    # absolute: the bare floor is ρ/π · I cos θ / r² (I = 1000 W / 4π, the light 12√2 m away at 45°) in both
    lit = 0.5 / math.pi * 1000.0 / (4.0 * math.pi) * math.cos(math.radians(45.0)) / 288.0
    assert bare.mean() == pytest.approx(lit, rel=0.02) and bare_cycles.mean() == pytest.approx(lit, rel=0.02)
    if shadow_through == 2:
        assert cycles.mean() / bare_cycles.mean() == pytest.approx(TINT ** 4, rel=0.01)
        assert prism.mean() / bare.mean() == pytest.approx(TINT ** 4, rel=1e-4)
        assert prism.mean() / cycles.mean() == pytest.approx(1.0, abs=0.02)  # the two engines, absolute
        assert prism.mean() == pytest.approx(lit * TINT ** 4, rel=0.02)
    else:
        assert cycles.max() < 1e-6
        assert np.all(prism == 0.0)
