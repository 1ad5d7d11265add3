"""Sensor fit and lens shift as Blender defines them: every camera ray Prism's F12 export makes lands,
through Blender's own projection matrix (``Object.calc_matrix_camera``), on the raster position it was
made for, whatever the sensor fit, the image's orientation, the pixel aspect and the shift."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest


CASES = [
    (kind, fit, resolution, (1.0, 1.0))
    for kind in ("PERSP", "ORTHO")
    for fit in ("AUTO", "HORIZONTAL", "VERTICAL")
    for resolution in ((48, 30), (30, 48))
] + [("PERSP", fit, (40, 36), aspect) for fit in ("AUTO", "VERTICAL") for aspect in ((1.6, 1.0), (1.0, 1.3))]


@pytest.mark.parametrize("kind, fit, resolution, pixel_aspect", CASES)
def test_camera_rays_land_where_blenders_projection_puts_them(prism_addon, fresh_scene, kind, fit, resolution,
                                                              pixel_aspect):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export.camera")
    cameras = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.cameras")
    stages = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.stages.camera")
    settings = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.settings")

    data = bpy.data.cameras.new("Camera")
    camera = bpy.data.objects.new("Camera", data)
    fresh_scene.collection.objects.link(camera)
    fresh_scene.camera = camera
    camera.location = (0.4, -3.0, 1.2)
    camera.rotation_euler = (math.radians(75), math.radians(5), math.radians(12))
    data.type, data.sensor_fit = kind, fit
    data.sensor_width, data.sensor_height = 36.0, 20.0  # unequal: the fitted sensor side matters
    data.lens, data.ortho_scale = 30.0, 2.5
    data.shift_x, data.shift_y = 0.21, -0.13
    fresh_scene.render.resolution_x, fresh_scene.render.resolution_y = resolution
    fresh_scene.render.resolution_percentage = 100
    fresh_scene.render.pixel_aspect_x, fresh_scene.render.pixel_aspect_y = pixel_aspect
    depsgraph = bpy.context.evaluated_depsgraph_get()
    width, height = resolution
    projection = np.array(camera.calc_matrix_camera(depsgraph, x=width, y=height, scale_x=pixel_aspect[0],
                                                    scale_y=pixel_aspect[1]))

    setup = cameras.make_camera(export.export_camera(fresh_scene, depsgraph), settings.RenderSettings())
    rng = np.random.default_rng(3)
    raster = rng.uniform((0.0, 0.0), (width, height), size=(64, 2))
    to_camera = np.linalg.inv(np.asarray(setup.data.rotation))
    for x, y in raster:
        o, d = stages.camera_ray(setup.data, float(x), float(y), 0.5, 0.5, 0.5)
        # A point one metre along the ray, in Blender's camera space, through Blender's projection.
        point = to_camera @ (np.asarray(o) + np.asarray(d) - np.asarray(setup.data.origin))
        clip = projection @ np.append(point, 1.0)
        ndc = clip[:2] / clip[3]
        expected = (2.0 * x / width - 1.0, 1.0 - 2.0 * y / height)
        assert np.allclose(ndc, expected, atol=1e-6), f"raster ({x:.2f}, {y:.2f}): Blender's projection puts it at {ndc}"
