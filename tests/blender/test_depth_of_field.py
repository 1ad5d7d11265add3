"""Blender's Depth of Field settings (the checkbox, a focus object, the f-stop) blur as a thin lens does:
a small emitter off the focus plane spreads over the circle of confusion of the closed form."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.cycles import render_prism_rgba


def _emitter(location, size_m):
    material = bpy.data.materials.new("Glow")
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bsdf.inputs["Emission Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Emission Strength"].default_value = 1.0
    half = size_m / 2
    mesh = bpy.data.meshes.new("Dot")
    mesh.from_pydata([(-half, 0.0, -half), (half, 0.0, -half), (half, 0.0, half), (-half, 0.0, half)], [],
                     [(0, 1, 2, 3)])
    mesh.materials.append(material)
    dot = bpy.data.objects.new("Dot", mesh)
    dot.location = location
    bpy.context.scene.collection.objects.link(dot)


def test_circle_of_confusion_from_blenders_settings_is_the_thin_lens_closed_form(prism_addon, fresh_scene):
    focal_mm, fstop, focus_m, depth_m, width, size_m = 50.0, 0.5, 0.5, 5.0, 96, 0.16
    fresh_scene.world = None
    _emitter((0.0, depth_m, 0.0), size_m)
    target = bpy.data.objects.new("Focus", None)
    target.location = (0.3, focus_m, -0.2)  # off the axis: the focus distance is its depth along the axis
    fresh_scene.collection.objects.link(target)
    data = bpy.data.cameras.new("Camera")
    camera = bpy.data.objects.new("Camera", data)
    fresh_scene.collection.objects.link(camera)
    fresh_scene.camera = camera
    camera.rotation_euler = (math.radians(90), 0.0, 0.0)  # looking down +Y
    data.lens, data.sensor_width = focal_mm, 36.0
    data.dof.use_dof, data.dof.focus_object, data.dof.aperture_fstop = True, target, fstop
    fresh_scene.render.resolution_x = fresh_scene.render.resolution_y = width
    fresh_scene.render.resolution_percentage = 100
    fresh_scene.prism.max_bounces = 0
    image = render_prism_rgba(fresh_scene, samples=256)[..., 1].astype(np.float64)

    ys, xs = np.mgrid[0:width, 0:width] + 0.5
    total = image.sum()
    cx, cy = (image * xs).sum() / total, (image * ys).sum() / total
    second = (image * ((xs - cx) ** 2 + (ys - cy) ** 2)).sum() / total
    px_per_tan = width / (36.0 / focal_mm)
    rho_px = focal_mm / (2 * fstop) / 1000 * abs(1 / depth_m - 1 / focus_m) * px_per_tan
    side_px = size_m / depth_m * px_per_tan
    expected = rho_px**2 / 2 + side_px**2 / 6 + 1 / 6
    print(f"MEASURED circle of confusion: radius {rho_px:.2f} px, second moment {second:.2f} px² against the closed "
          f"form's {expected:.2f} ({second / expected - 1:+.2%})")
    assert rho_px > 10
    # A uniform disc of radius ρ has second moment ρ²/2; the emitter's own square image and the box-filtered
    # pixels add s²/6 and 1/6.
    assert second == pytest.approx(expected, rel=0.03)
    assert abs(cx - width / 2) < 0.1 and abs(cy - width / 2) < 0.1
