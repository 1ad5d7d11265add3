"""Subsurface scattering (Principled Subsurface, the Subsurface Scattering node) as a random walk per
wavelength: a white-albedo sphere in a white furnace renders the furnace's radiance (every walk leaves, the exit
lobe reflects all); an absorbing one renders what an independent Monte Carlo of the same transport (exact
sphere, numpy) gives; skin-like spheres under a sun and a grey world render Cycles 4.5's absolute luminance."""

from __future__ import annotations

import numpy as np

from helpers.bake_scenes import uniform_world
from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.subsurface_reference import furnace_sphere
from helpers.subsurface_scenes import DISC, DISTANCE, skin_spheres_in_sun, sphere_means, spheres, subsurface_node

SAMPLES = 64
BOUNCES = 8


def test_white_subsurface_sphere_in_a_furnace_renders_the_furnace(prism_addon, fresh_scene):
    """Albedo 1: every walk leaves the sphere and its exit reflects everything, so the sphere is as bright as
    the world around it (1.0), scattering isotropically or forward (g = 0.6, past step 9 by similarity).
    (Random Walk (Skin) shrinks a white albedo's radius ~600-fold, so its walks run out of steps: not a furnace.)"""
    scene = spheres(subsurface_node("white walk", (1.0, 1.0, 1.0), (1.0, 1.0, 1.0), 0.2),
                    subsurface_node("white forward", (1.0, 1.0, 1.0), (1.0, 0.5, 0.25), 0.2, anisotropy=0.6))
    uniform_world((1.0, 1.0, 1.0), 1.0)
    scene.prism.max_bounces = 16
    prism = sphere_means(render_prism_rgba(scene, 16, 0))
    print("furnace, sphere means (walk, skin):", prism.round(4))
    assert np.all(np.abs(prism - 1.0) < 0.01), prism


def test_absorbing_subsurface_spheres_match_an_independent_walk(prism_addon, fresh_scene):
    """Albedo 0.8 in the furnace: a mean free path of 0.25 m lets light cross the unit sphere, so it returns far
    more than a half-space would (0.95, against about 0.8 for a short one); both as the numpy walk says."""
    scene = spheres(subsurface_node("long", (0.8, 0.8, 0.8), (1.0, 1.0, 1.0), 0.25),
                    subsurface_node("short", (0.8, 0.8, 0.8), (1.0, 1.0, 1.0), 0.05))
    uniform_world((1.0, 1.0, 1.0), 1.0)
    scene.prism.max_bounces = 8
    prism = sphere_means(render_prism_rgba(scene, 32, 0))
    reference = np.array([furnace_sphere(0.8, 0.25, disc=DISC, distance=DISTANCE, n=60_000),
                          furnace_sphere(0.8, 0.05, disc=DISC, distance=DISTANCE, n=60_000, seed=1)])
    print("furnace, albedo 0.8, radius 0.25 | 0.05: Prism", prism.round(4), "independent walk", reference.round(4))
    assert np.all(np.abs(prism / reference - 1.0) < 0.015), (prism, reference)


def test_subsurface_spheres_render_as_in_cycles(prism_addon, fresh_scene):
    scene = skin_spheres_in_sun()
    cycles = render_cycles_rgba(scene, SAMPLES, 0, BOUNCES)
    scene.prism.max_bounces = BOUNCES
    prism = render_prism_rgba(scene, SAMPLES, 0)
    ratio = sphere_means(prism) / sphere_means(cycles)
    channels = [prism[..., c].mean() / cycles[..., c].mean() for c in range(3)]
    print("prism/cycles sphere luminance (principled random walk, skin node):", ratio.round(4), "image R, G, B:",
          np.round(channels, 4))
    assert np.all(np.abs(ratio - 1.0) < 0.02), ratio


def test_at_max_bounces_0_the_walk_takes_no_bounce_as_in_cycles(prism_addon, fresh_scene):
    """Cycles counts no bounce for a random walk: at Max Bounces 0 the exit is still lit by the sun (and the world).
    Prism rendered both spheres black here before the walk stopped using a bounce (0.017 and 0.000 against
    Cycles' 0.328 and 0.355)."""
    scene = skin_spheres_in_sun()
    cycles = sphere_means(render_cycles_rgba(scene, 64, 0, 0))
    scene.prism.max_bounces = 0
    prism = sphere_means(render_prism_rgba(scene, 64, 0))
    print("MEASURED Max Bounces 0, prism/cycles sphere luminance:", (prism / cycles).round(4), "Prism",
          prism.round(4), "Cycles", cycles.round(4))
    assert np.all(np.abs(prism / cycles - 1.0) < 0.02), (prism, cycles)


def test_light_where_a_walk_leaves_is_direct_in_the_passes_as_in_cycles(prism_addon, fresh_scene, tmp_path):
    """Cycles counts no bounce for a random walk, and its passes neither: the sun sampled where the walk leaves the
    skin is Diffuse Direct, and so is what the exit's reflection finds; only more bounces are Indirect."""
    from helpers.cycles import configure_cycles

    from blender.test_passes import _render_layers, _switch_on

    scene = skin_spheres_in_sun()
    _switch_on(scene, ("diffuse_direct", "diffuse_indirect", "diffuse_color"))
    scene.render.use_compositing = False
    scene.prism.max_bounces = BOUNCES
    scene.prism.samples = scene.prism.samples_per_pass = SAMPLES
    prism = _render_layers(prism_addon, scene, tmp_path / "prism.exr")
    configure_cycles(scene, SAMPLES, 0, BOUNCES)
    cycles = _render_layers(prism_addon, scene, tmp_path / "cycles.exr", engine="CYCLES")
    for name in ("DiffDir", "DiffInd"):
        light_p, light_c = ((layers[name] * layers["DiffCol"]).mean() for layers in (prism, cycles))
        print("MEASURED", name, "x DiffCol, image mean: Prism", light_p, "Cycles", light_c)
        assert abs(light_p / light_c - 1.0) < 0.03, (name, light_p, light_c)
