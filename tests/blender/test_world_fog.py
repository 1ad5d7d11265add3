"""World fog (the World Output's Volume) as Cycles 4.5 renders it, in absolute light: Beer-Lambert through
absorbing fog against the closed form per pixel, a point light in scattering fog against Cycles, and
sunlight, which fog that fills all space does not let through (in Cycles as in Prism)."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.fog_scenes import fog_world, lit_floor, point_light_in_fog


def test_absorbing_fog_dims_an_emitter_by_beer_lambert(prism_addon, fresh_scene):
    """An emitting wall 5 m ahead in black fog of absorption 0.2 /m: each pixel is exp(-0.2 (5 m - clip
    start) / cos) of the wall's radiance (the camera ray starts at the clip start, in the fog)."""
    density = 0.2
    fog_world("ShaderNodeVolumeAbsorption", Density=density, Color=(0.0, 0.0, 0.0, 1.0))
    wall = add_plane("Wall", 20.0, location=(0.0, 5.0, 0.0))
    wall.rotation_euler = (math.pi / 2, 0.0, 0.0)
    wall.data.materials[0] = shader_material("Glow", "ShaderNodeEmission", Strength=2.0)
    clip = add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), resolution=(32, 16)).data.clip_start
    prism = luminance(render_prism_rgba(fresh_scene, 16))
    cycles = luminance(render_cycles_rgba(fresh_scene, 16))
    tan = 18.0 / 50.0
    x = ((np.arange(32) + 0.5) / 32 - 0.5) * 2 * tan
    y = ((np.arange(16) + 0.5) / 16 - 0.5) * tan
    secant = np.sqrt(1.0 + x[None, :] ** 2 + y[:, None] ** 2)
    closed = 2.0 * np.exp(-density * (5.0 - clip) * secant)
    print(f"MEASURED Beer-Lambert: Prism mean {prism.mean():.5f}, Cycles {cycles.mean():.5f}, closed form "
          f"{closed.mean():.5f}; worst pixel {np.abs(prism / closed - 1).max():.5f}")
    assert np.abs(prism / closed - 1.0).max() < 0.005
    assert prism.mean() == pytest.approx(cycles.mean(), rel=0.01)


def test_a_point_light_in_scattering_fog_as_cycles(prism_addon, fresh_scene):
    """A point light above and behind the camera over a grey floor in white fog (Volume Scatter, density
    0.15 /m): the lit fog and the dimmed floor, Prism against Cycles in absolute mean luminance (multiple
    scattering, 8 bounces). The light stays out of the view (a light seen in fog: the last test)."""
    point_light_in_fog()
    fresh_scene.prism.max_bounces = 8
    prism = render_prism_rgba(fresh_scene, 1024)
    cycles = render_cycles_rgba(fresh_scene, 1024, max_bounces=8)
    p, c = luminance(prism).mean(), luminance(cycles).mean()
    floor_only = fresh_scene.world
    fresh_scene.world = None
    clear = luminance(render_prism_rgba(fresh_scene, 16)).mean()
    fresh_scene.world = floor_only
    print(f"MEASURED point light in fog: Prism {p:.4f}, Cycles {c:.4f}, ratio {p / c:.4f}; without fog {clear:.4f}")
    assert p == pytest.approx(c, rel=0.02)
    assert abs(p - clear) > 0.05 * clear  # the fog changes the image


def test_sunlight_does_not_cross_fog_that_fills_all_space(prism_addon, fresh_scene):
    """A Sun over the floor in absorbing fog: its light would cross infinite fog, so nothing is lit, in
    Cycles and in Prism; without the fog the floor is lit."""
    fog_world("ShaderNodeVolumeAbsorption", Density=0.05, Color=(0.0, 0.0, 0.0, 1.0))

    def sun():
        data = bpy.data.lights.new("Sun", "SUN")
        data.energy = 3.0
        obj = bpy.data.objects.new("Sun", data)
        bpy.context.scene.collection.objects.link(obj)

    lit_floor(sun)
    prism = luminance(render_prism_rgba(fresh_scene, 4))
    cycles = luminance(render_cycles_rgba(fresh_scene, 4))
    print(f"MEASURED sun in fog: Prism max {prism.max():.6f}, Cycles max {cycles.max():.6f}")
    assert prism.max() == 0.0 and cycles.max() < 1e-6
    fresh_scene.world = None
    assert luminance(render_prism_rgba(fresh_scene, 4)).mean() > 0.1


def test_world_fog_is_not_warned_any_more(prism_addon, fresh_scene):
    from importlib import import_module

    world_module = import_module(f"{prism_addon.__name__}.engine.export.world")
    fog_world("ShaderNodeVolumeScatter", Density=0.1)
    warnings: list[str] = []
    world = world_module.export_world(fresh_scene, warnings)
    assert world.medium is not None and not any("Volume" in w or "fog" in w for w in warnings), warnings


def test_fog_and_a_light_alone_render(prism_addon, fresh_scene):
    """No mesh at all: the lit fog is what there is to see (Cycles renders it too), so Prism does not refuse
    the scene as empty."""
    fog_world("ShaderNodeVolumeScatter", Density=0.2)
    add_point_light("Bulb", 100.0, (0.0, 4.0, 0.0))
    add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), resolution=(16, 8))
    assert luminance(render_prism_rgba(fresh_scene, 4)).mean() > 0.0


def _single_scattering(tan_half, width, height, light_y, power_w, sigma, sub=4):
    """Single scattering of isotropic fog (σ_s = σ_t = ``sigma``) lit by a point light ``light_y`` m straight
    ahead, per pixel of a pinhole camera looking along +y: ∫ e^{-σ s} σ/(4π) I e^{-σ r}/r² ds from the clip
    start, averaged over ``sub`` × ``sub`` rays a pixel (numerical quadrature of the exact integral)."""
    intensity = power_w / (4.0 * math.pi)
    s = np.concatenate([np.linspace(0.1, light_y + 5.0, 40000), np.linspace(light_y + 5.0, 200.0, 20000)[1:]])
    ds = np.gradient(s)
    image = np.zeros((height, width))
    for row in range(height):
        for col in range(width):
            total = 0.0
            for a in range(sub):
                for b in range(sub):
                    x = ((col + (a + 0.5) / sub) / width - 0.5) * 2 * tan_half
                    z = (0.5 - (row + (b + 0.5) / sub) / height) * 2 * tan_half * height / width
                    d = np.array([x, 1.0, z]) / math.sqrt(1.0 + x * x + z * z)
                    r2 = (s * d[0]) ** 2 + (s * d[1] - light_y) ** 2 + (s * d[2]) ** 2
                    total += np.sum(np.exp(-sigma * (s + np.sqrt(r2))) * sigma / (4 * math.pi) * intensity / r2 * ds)
            image[row, col] = total / sub ** 2
    return image


def test_a_point_light_seen_in_fog_is_sampled_toward(prism_addon, fresh_scene):
    """A point light 3 m straight ahead in fog (σ_s = 0.15 /m), no bounce beyond the first scattering: the
    glow, whose rays pass through the light, against the single-scattering integral and Cycles. Prism
    samples half of the collisions equiangularly toward the light (``media.equiangular``): distance
    sampling alone has unbounded variance in the pixels around the light."""
    fog_world("ShaderNodeVolumeScatter", Density=0.15, Color=(1.0, 1.0, 1.0, 1.0))
    add_point_light("Bulb", 400.0, (0.0, 3.0, 0.0))
    add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), resolution=(16, 8))
    fresh_scene.prism.max_bounces = 0
    prism = luminance(render_prism_rgba(fresh_scene, 256))
    cycles = luminance(render_cycles_rgba(fresh_scene, 256, max_bounces=0))
    closed = _single_scattering(18.0 / 50.0, 16, 8, 3.0, 400.0, 0.15)
    print(f"MEASURED light seen in fog: Prism {prism.mean():.4f}, Cycles {cycles.mean():.4f}, single-scattering "
          f"integral {closed.mean():.4f}; Prism / integral {prism.mean() / closed.mean():.4f}, the light's pixels "
          f"{prism[3:5, 7:9].mean() / closed[3:5, 7:9].mean():.4f}")
    assert prism.mean() == pytest.approx(closed.mean(), rel=0.02)
    assert prism[3:5, 7:9].mean() == pytest.approx(closed[3:5, 7:9].mean(), rel=0.05)
    assert prism.mean() == pytest.approx(cycles.mean(), rel=0.03)
