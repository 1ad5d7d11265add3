"""A 60° SF11 prism seen at minimum deviation: the image of a white stripe splits into colours
by the amount Snell's law predicts, and does not with a constant-IOR glass."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, render_linear_rgb

APEX_RAD = math.radians(60.0)
WIDTH_PX, LENS_MM, SENSOR_MM = 64, 50.0, 36.0


def _min_deviation(n: float) -> float:
    return 2.0 * math.asin(n * math.sin(APEX_RAD / 2)) - APEX_RAD


def _quad_mesh(name, vertices, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _prism_scene(n_design: float):
    """Prism (apex up in XY, extruded along Z), camera looking back along the exit ray,
    emissive stripe along the entry ray, all placed for minimum deviation at ``n_design``."""
    side, height = 0.6, 0.18
    delta = _min_deviation(n_design)
    triangle = [(-side / 2, 0.0), (side / 2, 0.0), (0.0, side * math.sqrt(3) / 2)]
    glass = bpy.data.materials.new("Glass")
    glass.use_nodes = True
    principled = glass.node_tree.nodes["Principled BSDF"]
    principled.inputs["Transmission Weight"].default_value = 1.0
    principled.inputs["Roughness"].default_value = 0.0
    principled.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)  # clear glass (Base Color tints it)
    vertices = [(x, y, z) for z in (-1.0, 1.0) for x, y in triangle]
    _quad_mesh("Prism", vertices, [(0, 2, 1), (3, 4, 5), (0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)], glass)

    x_exit = side / 2 - height / math.sqrt(3)  # where the level internal ray meets the right face
    out = (math.cos(delta / 2), -math.sin(delta / 2))
    add_camera(
        (x_exit + 0.8 * out[0], height + 0.8 * out[1], 0.0),
        (math.pi / 2, 0.0, math.pi / 2 - delta / 2),
        lens_mm=LENS_MM,
        resolution=(WIDTH_PX, 16),
    )
    back = (-math.cos(delta / 2), -math.sin(delta / 2))  # from the left face toward the source
    cx, cy = -x_exit + 3.0 * back[0], height + 3.0 * back[1]
    px, py, w = -back[1], back[0], 0.03
    stripe = [(cx - w * px, cy - w * py, -1.0), (cx + w * px, cy + w * py, -1.0)]
    stripe += [(cx + w * px, cy + w * py, 1.0), (cx - w * px, cy - w * py, 1.0)]
    lamp = bpy.data.materials.new("Lamp")
    lamp.use_nodes = True
    emitter = lamp.node_tree.nodes["Principled BSDF"]
    emitter.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    emitter.inputs["Emission Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    emitter.inputs["Emission Strength"].default_value = 20.0
    _quad_mesh("Stripe", stripe, [(0, 1, 2, 3), (3, 2, 1, 0)], lamp)
    return glass


def _centroids_px(image, half_window_px=8):
    """Each channel's centroid over the stripe's image: pixels within ``half_window_px`` of the channel's
    peak (the prism's faint internal-reflection ghosts, far from it, are not the refracted image)."""
    profile = image.sum(axis=0)  # [W, 3]
    xs = np.arange(profile.shape[0]) + 0.5
    near = np.abs(xs[:, None] - xs[np.argmax(profile, axis=0)][None, :]) <= half_window_px
    return (profile * near * xs[:, None]).sum(axis=0) / (profile * near).sum(axis=0)


def test_prism_splits_the_stripe_as_snell_predicts(prism_addon, fresh_scene):
    glass_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.spectra.glass")
    sf11 = glass_module.glass_by_name("SF11")
    n_red, n_green, n_blue = (float(sf11.index(np.array([w]))[0]) for w in (600.0, 550.0, 450.0))
    glass = _prism_scene(n_green)
    fresh_scene.world = None
    fresh_scene.prism.wavelength_mode = "GAUSSIAN_RGB"  # R ~ 600 nm, G ~ 550 nm, B ~ 450 nm

    glass.prism.glass_source = "CATALOGUE"
    glass.prism.glass_name = "SF11"
    red, green, blue = _centroids_px(render_linear_rgb(fresh_scene, samples=8))
    pixels_per_radian = LENS_MM / (SENSOR_MM / WIDTH_PX)
    expected_px = (_min_deviation(n_blue) - _min_deviation(n_red)) * pixels_per_radian
    assert red < green < blue  # blue bends most
    assert blue - red == pytest.approx(expected_px, rel=0.25)

    glass.prism.glass_source = "PRINCIPLED_IOR"
    glass.node_tree.nodes["Principled BSDF"].inputs["IOR"].default_value = n_green
    red, green, blue = _centroids_px(render_linear_rgb(fresh_scene, samples=8))
    assert abs(blue - red) < 0.1 * expected_px
    assert green == pytest.approx(WIDTH_PX / 2, abs=2.0)  # the design wavelength lands mid-frame
