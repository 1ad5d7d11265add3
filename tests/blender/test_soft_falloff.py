"""Blender's Soft Falloff of point and spot lights (on in new lights), as Cycles 4.x models it: the
radius is a disc facing what it lights, so a floor inside a point light's sphere is lit and a spot's
cone edge is widened by its radius. Area lights have no such setting in Blender."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world


def _light(kind, location, power_w, radius_m, **settings):
    data = bpy.data.lights.new(kind, kind)
    data.energy, data.shadow_soft_size = power_w, radius_m
    for name, value in settings.items():
        setattr(data, name, value)
    obj = bpy.data.objects.new(kind, data)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    obj.visible_camera = False
    return data


def _floor_distance_m(centre_x_m):
    """[16, 32]: horizontal distance (m) from (centre_x_m, 0) of the floor point each pixel sees (the
    camera 5 m above the floor, 50 mm lens on a 36 mm film: the frame is 3.6 m × 1.8 m)."""
    rows, columns = np.mgrid[0:16, 0:32]
    x = (columns + 0.5 - 16.0) / 16.0 * 1.8
    y = (8.0 - rows - 0.5) / 8.0 * 0.9
    return np.hypot(x - centre_x_m, y)


def _regions(image):
    """Mean luminance of the floor inside the point light's sphere (within 0.45 m of its foot; the
    sphere cuts the floor at 0.458 m), in the spot's cone (within 0.3 m; the cone's edge is at
    0.364 m) and in the ring the spot's radius adds outside its cone (0.42 m to 0.6 m)."""
    lum = luminance(image)
    point, spot = _floor_distance_m(-1.0), _floor_distance_m(1.0)
    return (float(lum[point < 0.45].mean()), float(lum[spot < 0.3].mean()),
            float(lum[(spot > 0.42) & (spot < 0.6)].mean()))


@pytest.fixture
def floor_under_lights(fresh_scene):
    """A grey Lambertian floor seen from above: a point light of radius 0.5 m 0.2 m over its left half
    (the floor cuts its sphere), a 40° spot of radius 0.3 m 1 m over its right half (hard cone, blend 0)."""
    black_world()
    add_plane("Floor", 6.0, color=(0.5, 0.5, 0.5), specular=0.0)
    point = _light("POINT", (-1.0, 0.0, 0.2), 20.0, 0.5)
    spot = _light("SPOT", (1.0, 0.0, 1.0), 200.0, 0.3, spot_size=np.radians(40.0), spot_blend=0.0)
    add_camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    return fresh_scene, point, spot


@pytest.mark.parametrize("soft", [True, False])
def test_point_and_spot_radius_light_as_in_cycles(prism_addon, floor_under_lights, soft):
    """Soft Falloff on (Blender's default: a disc facing the floor) and off (a sphere): the floor inside
    the point light's sphere is lit (black before), the spot's cone and the ring its radius adds outside
    the cone (nearly black before) are as bright as Cycles renders them."""
    scene, point, spot = floor_under_lights
    assert point.use_soft_falloff and spot.use_soft_falloff  # Blender's default
    point.use_soft_falloff = spot.use_soft_falloff = soft
    cycles = _regions(render_cycles_rgba(scene, 256, max_bounces=1))
    prism = _regions(render_prism_rgba(scene, 256))
    assert cycles[0] > 0.2 and cycles[2] > 0.1 * cycles[1]  # lit inside the sphere; a widened cone
    assert prism[0] == pytest.approx(cycles[0], rel=0.03)
    assert prism[1] == pytest.approx(cycles[1], rel=0.03)
    assert prism[2] == pytest.approx(cycles[2], rel=0.08)
