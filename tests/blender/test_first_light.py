"""First light through Blender: a diffuse plane under one point light matches the closed form."""

import math

import numpy as np

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, render_linear_rgb


def expected_plane_radiance(camera, light_position, intensity_w_sr, albedo, width, height):
    """Radiance I·ρ·cosθ/(π r²) at the plane point seen through each pixel centre (z = 0 plane)."""
    matrix = np.array(camera.matrix_world)
    sensor = camera.data.sensor_width
    focal = camera.data.lens
    x = ((np.arange(width) + 0.5) / width - 0.5) * sensor
    y = (0.5 - (np.arange(height) + 0.5) / height) * sensor * height / width
    xs, ys = np.meshgrid(x, y)
    directions_camera = np.stack([xs, ys, -np.full_like(xs, focal)], axis=-1)
    directions = directions_camera @ matrix[:3, :3].T
    origin = matrix[:3, 3]
    t = -origin[2] / directions[..., 2]
    points = origin + t[..., None] * directions
    to_light = np.asarray(light_position) - points
    distance_squared = np.sum(to_light**2, axis=-1)
    cos_theta = to_light[..., 2] / np.sqrt(distance_squared)
    return intensity_w_sr * albedo * cos_theta / (math.pi * distance_squared)


def test_point_light_on_diffuse_plane_matches_closed_form(fresh_scene):
    albedo, power_w, light_position = 0.5, 1000.0, (0.4, -0.3, 2.0)
    add_plane("Floor", 20.0, color=(albedo, albedo, albedo), specular=0.0)  # Lambertian, as the closed form
    add_point_light("Bulb", power_w, light_position)
    camera = add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), lens_mm=35.0, resolution=(24, 24))
    fresh_scene.world = None

    image = render_linear_rgb(fresh_scene, samples=8)

    expected = expected_plane_radiance(camera, light_position, power_w / (4 * math.pi), albedo, 24, 24)
    assert np.isfinite(image).all()
    for channel in range(3):
        ratio = image[..., channel].mean() / expected.mean()
        assert abs(ratio - 1) < 0.01, f"channel {'RGB'[channel]}: rendered/closed form = {ratio:.4f}"
    # The image follows the 1/r² and cosθ fall-off, not just its mean.
    assert np.corrcoef(image[..., 1].ravel(), expected.ravel())[0, 1] > 0.99
