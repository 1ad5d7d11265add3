"""Light Paths ▸ Filter Glossy as Cycles renders it, in absolute light: a clear glass ball on a grey floor
under a point light casts a caustic that path tracing cannot find; with Filter Glossy 1 both engines blur the
glass seen after the floor's bounce into a rough one and light sampling fills the ball's shadow with a
blurred caustic. The same .blend is rendered by Cycles and by Prism; the images are compared block by block.
"""

from __future__ import annotations

import bpy
import numpy as np
import pytest
from mathutils import Vector

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

SAMPLES = 256  # the caustic blocks' seed-to-seed spread is about 5 % at 64 samples
BLOCK = 8  # pixels per side of the compared blocks


def _glass_ball_on_floor(scene):
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    add_plane("Floor", 6.0, color=(0.8, 0.8, 0.8), specular=0.0)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, location=(0.0, 0.0, 0.5), segments=64, ring_count=32)
    ball = bpy.context.object
    bpy.ops.object.shade_smooth()
    ball.data.materials.append(shader_material("Glass", "ShaderNodeBsdfGlass", Roughness=0.0, IOR=1.5))
    add_point_light("Bulb", 400.0, (2.0, 0.0, 2.0))
    camera = add_camera((-0.8, -3.0, 2.5), (0.0, 0.0, 0.0), lens_mm=35.0, resolution=(48, 32))
    camera.rotation_euler = Vector((0.1, 3.0, -2.5)).to_track_quat("-Z", "Y").to_euler()  # at (-0.7, 0, 0)


def _blocks(image) -> np.ndarray:
    lum = luminance(image)
    h, w = lum.shape
    return lum[: h // BLOCK * BLOCK, : w // BLOCK * BLOCK].reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK).mean((1, 3))


def test_filter_glossy_blurs_the_caustic_as_cycles_does(prism_addon, fresh_scene):
    _glass_ball_on_floor(fresh_scene)
    cycles = render_cycles_rgba(fresh_scene, SAMPLES, max_bounces=8, filter_glossy=1.0)
    blurred = render_prism_rgba(fresh_scene, SAMPLES)
    fresh_scene.cycles.blur_glossy = 0.0
    fresh_scene.prism.light_tracing = "OFF"
    sharp = render_prism_rgba(fresh_scene, SAMPLES)
    c, b, s = _blocks(cycles), _blocks(blurred), _blocks(sharp)
    caustic = np.abs(s / c - 1.0) > 0.2  # the blocks the blurred caustic lights (unblurred, they are darker)
    ratio = luminance(blurred).mean() / luminance(cycles).mean()
    in_caustic = b[caustic].sum() / c[caustic].sum()
    print(f"MEASURED Filter Glossy 1: Prism / Cycles mean luminance {ratio:.4f}, in the {caustic.sum()} caustic "
          f"blocks {in_caustic:.4f} (Filter Glossy 0: {s[caustic].sum() / c[caustic].sum():.4f})")
    print("MEASURED blocks Cycles\n", np.round(c, 4), "\nPrism\n", np.round(b, 4), "\nPrism, Filter Glossy 0\n",
          np.round(s, 4))
    assert caustic.sum() >= 2
    assert s[caustic].sum() < 0.8 * c[caustic].sum()
    assert in_caustic == pytest.approx(1.0, abs=0.05)
    assert ratio == pytest.approx(1.0, abs=0.02)
