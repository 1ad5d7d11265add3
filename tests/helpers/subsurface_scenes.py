"""Subsurface scenes built in bpy: two unit spheres side by side before a camera, the materials they wear
(a Subsurface Scattering node, a skin-like Principled with Subsurface Weight 1), the sun and grey world that
light them for the comparison with Cycles, and the mean luminance over each sphere's image. Shared by
tests/blender/test_subsurface.py, the benchmark experiment media_vs_cycles and tools/subsurface_picture.py."""

from __future__ import annotations

import math

import bpy
import numpy as np

from helpers.bake_scenes import uniform_world
from helpers.cycles import luminance
from helpers.node_scenes import camera, material, node, uv_sphere

RESOLUTION = (96, 48)
LEFT, RIGHT = (-1.1, 0.0, 0.0), (1.1, 0.0, 0.0)
DISTANCE, LENS_MM, SENSOR_MM = 6.5, 40.0, 36.0
#: The part of each sphere's image radius ``sphere_means`` averages over.
DISC = 0.8


def subsurface_node(name, colour, radius, scale, falloff="RANDOM_WALK", anisotropy=0.0):
    """A material whose Surface is one Subsurface Scattering node (IOR 1.4, roughness 1)."""
    mat, nodes, link = material(name)
    sss = node(nodes, "ShaderNodeSubsurfaceScattering", Color=colour, Radius=radius, Scale=scale, IOR=1.4,
               Roughness=1.0, Anisotropy=anisotropy)
    sss.falloff = falloff
    link(sss.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def principled_skin(name, method, base_color=(0.8, 0.45, 0.35), radius=(1.0, 0.2, 0.1), scale=0.05):
    """A Principled BSDF of Subsurface Weight 1 (roughness 0.5, IOR 1.4) walking by ``method``."""
    mat, nodes, link = material(name)
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=base_color, Roughness=0.5, IOR=1.4,
                Subsurface_Weight=1.0, Subsurface_Radius=radius, Subsurface_Scale=scale)
    bsdf.subsurface_method = method
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def spheres(left, right, resolution=RESOLUTION):
    """The current scene emptied of objects, then unit spheres wearing ``left`` and ``right`` at ``LEFT`` and
    ``RIGHT``, seen from ``DISTANCE`` m in front; the scene."""
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    uv_sphere("Left", 1.0, LEFT, left)
    uv_sphere("Right", 1.0, RIGHT, right)
    camera((0.0, -DISTANCE, 0.0), (0.0, 0.0, 0.0), lens_mm=LENS_MM, resolution=resolution, sensor_mm=SENSOR_MM)
    return scene


def sun_and_grey_world(scene, energy=3.0, angle_deg=5.0, rotation_deg=(35.0, 0.0, 20.0), grey=0.2):
    """A sun of ``energy`` W/m² (``angle_deg`` across) turned by ``rotation_deg`` and a uniform grey world."""
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = energy, math.radians(angle_deg)
    sun.rotation_euler = tuple(math.radians(a) for a in rotation_deg)
    scene.collection.objects.link(sun)
    uniform_world((grey, grey, grey), 1.0)
    return sun


def skin_spheres_in_sun(resolution=RESOLUTION):
    """The Cycles comparison scene: a skin-like Principled sphere (random walk) beside an orange Subsurface
    Scattering node sphere (random walk, skin), under a sun and a grey world; the scene."""
    scene = spheres(principled_skin("skin principled", "RANDOM_WALK"),
                    subsurface_node("orange node", (0.9, 0.5, 0.2), (1.0, 0.4, 0.2), 0.3, "RANDOM_WALK_SKIN"),
                    resolution)
    sun_and_grey_world(scene)
    return scene


def sphere_means(image):
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
