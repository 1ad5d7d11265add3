"""Object ▸ Visibility ▸ Mask ▸ Shadow Catcher against Cycles 4.5, in absolute terms: a grey floor marked
Shadow Catcher under a tan cube, lit by a sun and a blue-grey world. Cycles' Combined with Film ▸
Transparent (the cube over a transparent floor, the shadow in alpha), without it (the world behind the
floor, darkened by the shadow), with View Layer ▸ Passes ▸ Light ▸ Shadow Catcher on (the matte: the floor
transparent) and that pass itself (the floor's light with the cube / without it)."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from blender.test_passes import _render_layers
from helpers.bpy_scenes import add_camera, add_plane
from helpers.cycles import configure_cycles

SAMPLES = 64
WORLD = (0.2, 0.3, 0.5)


@pytest.fixture
def catcher_scene(fresh_scene):
    """The floor (6 m, ρ 0.5, Lambertian) is the catcher; a 0.8 m cube (ρ 0.6, 0.5, 0.4: a mild colour, so
    Prism's spectral products stay near Cycles' RGB ones) stands on it; a sun of 3 W/m² 40° above the
    horizon throws its shadow toward the camera; the world is a constant colour."""
    scene = fresh_scene
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*WORLD, 1.0)
    scene.world = world
    floor = add_plane("Floor", 6.0, color=(0.5, 0.5, 0.5), specular=0.0)
    floor.is_shadow_catcher = True
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(0.0, 0.0, 0.4))
    cube = bpy.context.active_object
    cube.name = "Cube"
    material = bpy.data.materials.new("Cube")
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.6, 0.5, 0.4, 1.0)
    bsdf.inputs["Specular IOR Level"].default_value = 0.0
    cube.data.materials.append(material)
    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle = 3.0, 0.0
    sun_object = bpy.data.objects.new("Sun", sun)
    sun_object.rotation_euler = (math.radians(-50.0), 0.0, math.radians(25.0))
    scene.collection.objects.link(sun_object)
    add_camera((0.0, -3.5, 2.5), (math.radians(55.0), 0.0, 0.0), resolution=(32, 24))
    scene.render.use_compositing = False
    configure_cycles(scene, SAMPLES, max_bounces=4)
    scene.prism.samples = scene.prism.samples_per_pass = SAMPLES
    scene.prism.max_bounces = 4
    return scene


def _both(prism_addon, scene, tmp_path, transparent, with_pass):
    """(Prism, Cycles) layers of one configuration: pass name → [24, 32, C]."""
    scene.render.film_transparent = transparent
    scene.view_layers[0].cycles.use_pass_shadow_catcher = with_pass
    tag = f"{int(transparent)}{int(with_pass)}"
    prism = _render_layers(prism_addon, scene, tmp_path / f"prism{tag}.exr")
    cycles = _render_layers(prism_addon, scene, tmp_path / f"cycles{tag}.exr", engine="CYCLES")
    return prism, cycles


def _regions(cycles_with_pass):
    """From Cycles' render with the pass on: the cube (the matte's opaque pixels), the floor deep in the cube's
    shadow (pass below 0.5 there and in every neighbour) and the open floor (rows far from the cube, out of
    the shadow's reach)."""
    alpha = cycles_with_pass["Combined"][..., 3]
    catcher = cycles_with_pass["Shadow Catcher"][..., 0]
    cube = alpha == 1.0
    dark = catcher < 0.5
    core = dark.copy()
    core[1:-1, 1:-1] = dark[1:-1, 1:-1] & dark[:-2, 1:-1] & dark[2:, 1:-1] & dark[1:-1, :-2] & dark[1:-1, 2:]
    shadow = core & (alpha == 0.0)
    open_floor = np.zeros_like(cube)
    open_floor[1:5, :] = True  # the floor far behind the cube, up to the horizon's row
    open_floor[-2:, :] = True  # and in front of the shadow (less its penumbra)
    return cube, shadow, open_floor & (alpha == 0.0) & (catcher > 0.9)


def test_shadow_catcher_pass_and_matte_match_cycles(prism_addon, catcher_scene, tmp_path):
    prism, cycles = _both(prism_addon, catcher_scene, tmp_path, transparent=True, with_pass=True)
    assert "Shadow Catcher" in prism and prism["Shadow Catcher"].shape == (24, 32, 3)
    cube, shadow, open_floor = _regions(cycles)
    assert cube.sum() >= 20 and shadow.sum() >= 10 and open_floor.sum() >= 100
    p, c = prism["Shadow Catcher"], cycles["Shadow Catcher"]
    # In the shadow the floor keeps the sky the cube leaves it: about a fifth of its light.
    assert 0.1 < c[shadow].mean() < 0.4
    assert abs(p[shadow].mean() / c[shadow].mean() - 1.0) < 0.03, (p[shadow].mean(), c[shadow].mean())
    assert abs(p[open_floor].mean() - 1.0) < 0.01 and abs(c[open_floor].mean() - 1.0) < 0.01
    # With the pass on, Combined is the matte: the cube, opaque, over a floor with alpha 0 (shadow included).
    assert np.all(prism["Combined"][..., 3][shadow | open_floor] == 0.0)
    assert np.all(prism["Combined"][..., :3][shadow | open_floor] == 0.0)
    pc, cc = prism["Combined"][cube][:, :3].mean(0), cycles["Combined"][cube][:, :3].mean(0)
    assert np.all(np.abs(pc / cc - 1.0) < 0.03), (pc, cc)


def _regions_without_pass(cycles_transparent):
    """The same regions from Cycles' transparent Combined with the pass off: the cube (opaque and lit), the
    shadow's core (alpha above 0.5 over black, neighbours too), the open floor (nearly transparent rows)."""
    alpha, rgb = cycles_transparent[..., 3], cycles_transparent[..., :3].sum(-1)
    cube = (alpha == 1.0) & (rgb > 0.0)
    dark = (alpha > 0.5) & (rgb == 0.0)
    core = dark.copy()
    core[1:-1, 1:-1] = dark[1:-1, 1:-1] & dark[:-2, 1:-1] & dark[2:, 1:-1] & dark[1:-1, :-2] & dark[1:-1, 2:]
    open_floor = np.zeros_like(cube)
    open_floor[1:5, :] = True
    open_floor[-2:, :] = True
    return cube, core, open_floor & (alpha < 0.1)


def test_combined_without_the_pass_holds_the_shadow_as_cycles(prism_addon, catcher_scene, tmp_path):
    """Film ▸ Transparent: the shadow in alpha (1 - mean(pass)) over black; opaque: the world behind the floor
    × mean(pass), alpha 1 (Cycles' approximate shadow catcher, its default)."""
    prism, cycles = _both(prism_addon, catcher_scene, tmp_path, transparent=True, with_pass=False)
    assert "Shadow Catcher" not in prism
    cube, shadow, open_floor = _regions_without_pass(cycles["Combined"])
    assert cube.sum() >= 20 and shadow.sum() >= 10 and open_floor.sum() >= 100
    pa, ca = prism["Combined"][..., 3], cycles["Combined"][..., 3]
    assert 0.6 < ca[shadow].mean() < 0.9
    assert abs(pa[shadow].mean() - ca[shadow].mean()) < 0.02, (pa[shadow].mean(), ca[shadow].mean())
    assert pa[open_floor].mean() < 0.01 and ca[open_floor].mean() < 0.01
    assert np.abs(prism["Combined"][..., :3][shadow]).max() < 1e-6  # the matte has nothing there
    assert np.all(pa[cube] == 1.0)
    pc, cc = prism["Combined"][cube][:, :3].mean(0), cycles["Combined"][cube][:, :3].mean(0)
    assert np.all(np.abs(pc / cc - 1.0) < 0.03), (pc, cc)

    prism, cycles = _both(prism_addon, catcher_scene, tmp_path, transparent=False, with_pass=False)
    assert np.all(prism["Combined"][..., 3] == 1.0) and np.all(cycles["Combined"][..., 3] == 1.0)
    p, c = prism["Combined"][..., :3], cycles["Combined"][..., :3]
    assert np.all(np.abs(p[open_floor].mean(0) / np.array(WORLD) - 1.0) < 0.01), p[open_floor].mean(0)
    assert np.all(np.abs(p[shadow].mean(0) / c[shadow].mean(0) - 1.0) < 0.03), (p[shadow].mean(0), c[shadow].mean(0))
    assert np.all(np.abs(p[cube].mean(0) / c[cube].mean(0) - 1.0) < 0.03), (p[cube].mean(0), c[cube].mean(0))
