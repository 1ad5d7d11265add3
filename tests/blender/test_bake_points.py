"""A texel's surface point from Blender's bake pixel (loop triangle, barycentric u, v: u·c0 + v·c1 +
(1 − u − v)·c2), and the ray that finds it: starting just off the surface, it meets the plane of the
triangle at the point itself, seen along the normal or, for View From ▸ Active Camera, from the camera
turned as Cycles turns it (never from behind the face)."""

import numpy as np

from engine.render.bake_points import (SURFACE_NORMAL_OFFSET, BakeTriangles, bake_ray_table, surface_points,
                                       towards_camera)

CORNERS = np.array([[[0.0, 0.0, 2.0], [3.0, 0.0, 2.0], [0.0, 3.0, 2.0]]])


def _points(u, v, normals=(0.0, 0.0, 1.0), mirrored=False):
    triangles = BakeTriangles(CORNERS, np.broadcast_to(normals, CORNERS.shape).copy(), mirrored)
    return surface_points(triangles, np.zeros(len(u), np.int64), np.asarray(u, float), np.asarray(v, float))


def test_blenders_barycentric_convention():
    points = _points([1.0, 0.0, 0.0, 0.2], [0.0, 1.0, 0.0, 0.5])
    assert np.allclose(points.position, [[0, 0, 2], [3, 0, 2], [0, 3, 2], [1.5, 0.9, 2]])
    assert np.allclose(points.geometric, (0, 0, 1)) and np.allclose(points.normal, (0, 0, 1))
    assert np.allclose(_points([0.2], [0.5], mirrored=True).geometric, (0, 0, -1))


def test_the_ray_meets_the_surface_at_the_point():
    points = _points([0.2, 0.6], [0.5, 0.1], normals=(0.3, 0.0, 1.0))  # a tilted shading normal
    origin, direction = bake_ray_table(points, render_origin=(10.0, 0.0, 0.0))
    t = (2.0 - origin[:, 2]) / direction[:, 2]  # to the plane z = 2
    assert np.all(t > 0) and np.all(t < 1e-3)
    assert np.allclose(origin + t[:, None] * direction, points.position - (10.0, 0.0, 0.0), atol=1e-12)
    assert np.allclose(np.linalg.norm(direction, axis=1), 1.0)


def test_camera_view_directions_stay_in_front_of_the_face():
    points = _points([0.2, 0.2, 0.2], [0.5, 0.5, 0.5])
    overhead = towards_camera(_points([0.2], [0.5]), camera_position=(1.5, 0.9, 7.0))
    assert np.allclose(overhead, (0, 0, 1))  # straight above: unchanged
    grazing = towards_camera(_points([0.2], [0.5]), camera_position=(50.0, 0.9, 2.0))
    assert grazing[0, 2] > 0.9 * SURFACE_NORMAL_OFFSET  # lifted towards the normal (before normalising: by it)
    behind = towards_camera(_points([0.2], [0.5]), camera_position=(1.5, 0.9, -5.0))
    assert behind[0, 2] > 0.0  # a camera behind the face still sees its front
    ortho = towards_camera(points, camera_position=None, camera_axis=(0.0, 0.0, 1.0))
    assert np.allclose(ortho, (0, 0, 1))
