"""Closures with normals of their own, against Cycles 4.5 in absolute light: a Principled BSDF whose Coat
Normal is a bump of wave bands over a smooth base, and a Mix Shader of a smooth Diffuse and a bumped
Glossy. Cycles gives every closure its own normal; before, Prism shaded the coat with the base normal (and
warned), and the mix's Diffuse with the Glossy's bump (silently). Each sphere's mean luminance and its
pattern (blocks across the sphere) are compared with Cycles, and with the same scene whose extra normals are
unlinked, to show the test sees them."""

from __future__ import annotations

import math

import bpy
import numpy as np

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import camera, material, node, uv_sphere

SAMPLES = 64
BOUNCES = 8
RESOLUTION = (96, 48)
LEFT, RIGHT = (-1.1, 0.0, 0.0), (1.1, 0.0, 0.0)


def _bump(nodes, link):
    """A bump of wave bands across the sphere."""
    wave = node(nodes, "ShaderNodeTexWave", Scale=3.0, Distortion=0.0)
    bump = node(nodes, "ShaderNodeBump", Strength=1.0, Distance=0.3)
    link(wave.outputs["Fac"], bump.inputs["Height"])
    return bump.outputs["Normal"]


def _coated(bumped: bool):
    mat, nodes, link = material("coated")
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=(0.05, 0.05, 0.05), Roughness=0.5, Coat_Weight=1.0,
                Coat_Roughness=0.25)
    if bumped:
        link(_bump(nodes, link), bsdf.inputs["Coat Normal"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _mixed(bumped: bool):
    mat, nodes, link = material("mixed")
    diffuse = node(nodes, "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5))
    glossy = node(nodes, "ShaderNodeBsdfAnisotropic", Color=(0.9, 0.9, 0.9), Roughness=0.25)
    if bumped:
        link(_bump(nodes, link), glossy.inputs["Normal"])
    mix = node(nodes, "ShaderNodeMixShader", Fac=0.5)
    link(diffuse.outputs[0], mix.inputs[1])
    link(glossy.outputs[0], mix.inputs[2])
    link(mix.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _scene(bumped: bool):
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    uv_sphere("Coated", 1.0, LEFT, _coated(bumped))
    uv_sphere("Mixed", 1.0, RIGHT, _mixed(bumped))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, math.radians(5.0)
    sun.rotation_euler = (math.radians(35.0), 0.0, math.radians(20.0))
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.2, 0.2, 0.2, 1.0)
    scene.world = world
    camera((0.0, -6.5, 0.0), (0.0, 0.0, 0.0), lens_mm=40.0, resolution=RESOLUTION)
    return scene


def _blocks(image):
    """Mean luminance of 4 × 4 blocks over each sphere's disc: [2, 16] (left, right)."""
    y = luminance(image[..., :3])
    height, width = y.shape
    half = width // 2
    out = []
    for x0 in (0, half):
        disc = y[:, x0:x0 + half]
        rows, cols = np.array_split(np.arange(8, height - 8), 4), np.array_split(np.arange(8, half - 8), 4)
        out.append([disc[np.ix_(r, c)].mean() for r in rows for c in cols])
    return np.array(out)


def test_own_normals_render_as_in_cycles(prism_addon, fresh_scene):
    scene = _scene(bumped=True)
    cycles = render_cycles_rgba(scene, SAMPLES, 0, BOUNCES)
    scene.prism.max_bounces = BOUNCES
    prism = render_prism_rgba(scene, SAMPLES, 0)
    unbumped = render_prism_rgba(_scene(bumped=False), SAMPLES, 0)
    c, p, u = _blocks(cycles), _blocks(prism), _blocks(unbumped)
    means = p.mean(1) / c.mean(1)
    error = np.abs(p - c).mean(1) / c.mean(1)
    without = np.abs(u - c).mean(1) / c.mean(1)
    print("prism/cycles mean (coat, mix):", means.round(4), "block error:", error.round(4),
          "block error without the extra normals:", without.round(4))
    assert np.all(np.abs(means - 1.0) < 0.02), means
    assert np.all(error < 0.35 * without), (error, without)
