"""Subsurface scattering (Principled Subsurface, the Subsurface Scattering node) as a random walk per
wavelength: a white-albedo sphere in a white furnace renders the furnace's radiance (every walk leaves, the exit
lobe reflects all); an absorbing one renders what an independent Monte Carlo of the same transport (exact
sphere, numpy) gives; skin-like spheres under a sun and a grey world render Cycles 4.5's absolute luminance."""

from __future__ import annotations

import math

import bpy
import numpy as np

from helpers.bake_scenes import uniform_world
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import camera, material, node, uv_sphere
from helpers.subsurface_reference import furnace_sphere

SAMPLES = 64
BOUNCES = 8
RESOLUTION = (96, 48)
LEFT, RIGHT = (-1.1, 0.0, 0.0), (1.1, 0.0, 0.0)


def _clear():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)


def _subsurface_node(name, colour, radius, scale, falloff="RANDOM_WALK", anisotropy=0.0):
    mat, nodes, link = material(name)
    sss = node(nodes, "ShaderNodeSubsurfaceScattering", Color=colour, Radius=radius, Scale=scale, IOR=1.4,
               Roughness=1.0, Anisotropy=anisotropy)
    sss.falloff = falloff
    link(sss.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _principled(name, method):
    mat, nodes, link = material(name)
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=(0.8, 0.45, 0.35), Roughness=0.5, IOR=1.4,
                Subsurface_Weight=1.0, Subsurface_Radius=(1.0, 0.2, 0.1), Subsurface_Scale=0.05)
    bsdf.subsurface_method = method
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _spheres(left, right):
    scene = bpy.context.scene
    _clear()
    uv_sphere("Left", 1.0, LEFT, left)
    uv_sphere("Right", 1.0, RIGHT, right)
    camera((0.0, -DISTANCE, 0.0), (0.0, 0.0, 0.0), lens_mm=LENS_MM, resolution=RESOLUTION, sensor_mm=SENSOR_MM)
    return scene


DISTANCE, LENS_MM, SENSOR_MM = 6.5, 40.0, 36.0
#: The part of each sphere's image radius ``_sphere_means`` averages over.
DISC = 0.8


def _sphere_means(image):
    """Mean luminance over each unit sphere's image disc (``DISC`` of its image radius): (left, right)."""
    y = luminance(image[..., :3])
    height, width = y.shape
    half_width_tan = SENSOR_MM / 2.0 / LENS_MM
    pixels_per_tan = width / 2.0 / half_width_tan
    radius = DISC * pixels_per_tan / math.sqrt(DISTANCE ** 2 - 1.0)
    rows, cols = np.mgrid[0:height, 0:width]
    out = []
    for centre in (LEFT, RIGHT):
        x = width / 2.0 + centre[0] / DISTANCE * pixels_per_tan
        inside = (cols + 0.5 - x) ** 2 + (rows + 0.5 - height / 2.0) ** 2 < radius ** 2
        out.append(y[inside].mean())
    return np.array(out)


def test_white_subsurface_sphere_in_a_furnace_renders_the_furnace(prism_addon, fresh_scene):
    """Albedo 1: every walk leaves the sphere and its exit reflects everything, so the sphere is as bright as
    the world around it (1.0), scattering isotropically or forward (g = 0.6, past step 9 by similarity).
    (Random Walk (Skin) shrinks a white albedo's radius ~600-fold, so its walks run out of steps: not a furnace.)"""
    scene = _spheres(_subsurface_node("white walk", (1.0, 1.0, 1.0), (1.0, 1.0, 1.0), 0.2),
                     _subsurface_node("white forward", (1.0, 1.0, 1.0), (1.0, 0.5, 0.25), 0.2, anisotropy=0.6))
    uniform_world((1.0, 1.0, 1.0), 1.0)
    scene.prism.max_bounces = 16
    prism = _sphere_means(render_prism_rgba(scene, 16, 0))
    print("furnace, sphere means (walk, skin):", prism.round(4))
    assert np.all(np.abs(prism - 1.0) < 0.01), prism


def test_absorbing_subsurface_spheres_match_an_independent_walk(prism_addon, fresh_scene):
    """Albedo 0.8 in the furnace: a mean free path of 0.25 m lets light cross the unit sphere, so it returns far
    more than a half-space would (0.95, against about 0.8 for a short one); both as the numpy walk says."""
    scene = _spheres(_subsurface_node("long", (0.8, 0.8, 0.8), (1.0, 1.0, 1.0), 0.25),
                     _subsurface_node("short", (0.8, 0.8, 0.8), (1.0, 1.0, 1.0), 0.05))
    uniform_world((1.0, 1.0, 1.0), 1.0)
    scene.prism.max_bounces = 8
    prism = _sphere_means(render_prism_rgba(scene, 32, 0))
    reference = np.array([furnace_sphere(0.8, 0.25, disc=DISC, distance=DISTANCE, n=60_000),
                          furnace_sphere(0.8, 0.05, disc=DISC, distance=DISTANCE, n=60_000, seed=1)])
    print("furnace, albedo 0.8, radius 0.25 | 0.05: Prism", prism.round(4), "independent walk", reference.round(4))
    assert np.all(np.abs(prism / reference - 1.0) < 0.015), (prism, reference)


def test_subsurface_spheres_render_as_in_cycles(prism_addon, fresh_scene):
    scene = _spheres(_principled("skin principled", "RANDOM_WALK"),
                     _subsurface_node("orange node", (0.9, 0.5, 0.2), (1.0, 0.4, 0.2), 0.3, "RANDOM_WALK_SKIN"))
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 3.0, math.radians(5.0)
    sun.rotation_euler = (math.radians(35.0), 0.0, math.radians(20.0))
    scene.collection.objects.link(sun)
    uniform_world((0.2, 0.2, 0.2), 1.0)
    cycles = render_cycles_rgba(scene, SAMPLES, 0, BOUNCES)
    scene.prism.max_bounces = BOUNCES
    prism = render_prism_rgba(scene, SAMPLES, 0)
    ratio = _sphere_means(prism) / _sphere_means(cycles)
    channels = [prism[..., c].mean() / cycles[..., c].mean() for c in range(3)]
    print("prism/cycles sphere luminance (principled random walk, skin node):", ratio.round(4), "image R, G, B:",
          np.round(channels, 4))
    assert np.all(np.abs(ratio - 1.0) < 0.02), ratio
