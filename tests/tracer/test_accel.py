"""Embree queries on ray queues: closest hits, occlusion, hits limited to tmax, self-intersection."""

import numpy as np
import pytest

from engine.tracer.accel import Accel
from engine.tracer.geometry import offset_origin, prepare_geometry, surface_at
from engine.tracer.scene import Camera, Material, Scene
from engine.tracer.state import new_ray_queue

from .tracer_scenes import quad


def _scene(vertices, triangles):
    return Scene(vertices=np.asarray(vertices, np.float64), triangles=np.asarray(triangles, np.int32),
                 triangle_material=np.zeros(len(triangles), np.int32), materials=[Material("m")],
                 camera=Camera("c", np.eye(4), (1, 1)))


def _queue(o, d, tmax=None):
    q = new_ray_queue(len(o))
    q.origin[:] = o
    q.direction[:] = d
    q.tmax[:] = 1e30 if tmax is None else tmax
    return q


def test_closest_hit_occlusion_and_hits_before_tmax():
    v1, t1 = quad((0, 0, 0), (1, 0, 0), (0, 1, 0))
    v2, t2 = quad((0, 0, -1), (1, 0, 0), (0, 1, 0))
    geometry, _, dropped = prepare_geometry(_scene(np.vstack([v1, v2]), np.vstack([t1, t2 + 4])), np.zeros(3))
    acc = Accel(geometry)
    o = np.array([[0.2, 0.3, 2.0], [0.5, 0.5, -0.5], [5.0, 5.0, 1.0]])
    d = np.array([[0, 0, -1.0], [0, 0, -1.0], [0, 0, -1.0]])
    tri, t, u, v = acc.intersect(_queue(o, d), 3)
    assert dropped == 0
    assert tri[0] in (0, 1) and t[0] == pytest.approx(2.0)
    assert tri[1] in (2, 3) and t[1] == pytest.approx(0.5)
    assert tri[2] == -1
    assert (acc.occluded(_queue(o, d, [1.9, 0.6, 10.0]), 3) == 0).tolist() == [False, True, False]
    assert (acc.occluded(_queue(o, d, [2.1, 0.4, 10.0]), 3) == 0).tolist() == [True, False, False]
    before = acc.intersect_before(_queue(o, d, [1.9, 0.6, 10.0]), 3)[0]
    assert before[0] == -1 and before[1] in (2, 3) and before[2] == -1


def test_zero_area_and_non_finite_triangles_are_dropped_and_ids_stay_consistent():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 2, 2], [0, 0, 1], [1, 0, 1], [0, 1, 1]], np.float64)
    scene = _scene(v, np.array([[0, 1, 2], [3, 3, 3], [0, 1, 1], [4, 5, 6]]))
    scene.triangle_material = np.array([0, 0, 0, 0], np.int32)
    geometry, original, dropped = prepare_geometry(scene, np.zeros(3))
    assert dropped == 2 and original.tolist() == [0, 3] and len(geometry.triangles) == 2
    tri, *_ = Accel(geometry).intersect(_queue(np.array([[0.1, 0.1, 2.0]]), np.array([[0, 0, -1.0]])), 1)
    assert tri[0] == 1  # the kept triangle at z = 1: rows of the kept table


def test_an_empty_scene_misses_everything():
    geometry, _, _ = prepare_geometry(_scene(np.zeros((0, 3)), np.zeros((0, 3), np.int32)), np.zeros(3))
    acc = Accel(geometry)
    q = _queue(np.zeros((2, 3)), np.array([[0, 0, 1.0], [1, 0, 0]]))
    assert acc.intersect(q, 2)[0].tolist() == [-1, -1] and acc.occluded(q, 2).tolist() == [-1, -1]


@pytest.mark.parametrize("scale", [1.0, 1e4])
def test_reflected_rays_do_not_rehit_their_surface(scale):
    """Secondary rays off a tilted plane far from the camera never hit the plane again."""
    rng = np.random.default_rng(1)
    center = np.array([1.0, -0.7, 0.4]) * scale
    u = np.array([1.0, 0.2, 0.3]) * 0.5 * scale
    w = np.cross(u, [0.1, 0.3, 1.0])
    w *= np.linalg.norm(u) / np.linalg.norm(w)
    v, t = quad(center, u, w)
    geometry, _, _ = prepare_geometry(_scene(v, t), np.zeros(3))
    acc = Accel(geometry)
    n = 20_000
    e1, e2 = (v[1] - v[0]), (v[2] - v[0])
    normal = np.cross(e1, e2) / np.linalg.norm(np.cross(e1, e2))
    targets = center + rng.uniform(-0.9, 0.9, (n, 1)) * u + rng.uniform(-0.9, 0.9, (n, 1)) * w
    origins = targets + normal * scale * rng.uniform(0.1, 1.0, (n, 1)) + rng.normal(size=(n, 3)) * 0.1 * scale
    d = targets - origins
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    tri, _, bu, bv = acc.intersect(_queue(origins, d), n)
    hit = np.flatnonzero(tri >= 0)
    surfaces = [surface_at(geometry, int(tri[j]), float(bu[j]), float(bv[j]), 0.5) for j in hit]
    p = np.array([s[0] for s in surfaces])
    ng = np.array([s[1] for s in surfaces])
    dh = d[hit]
    refl = dh - 2 * (dh * ng).sum(1, keepdims=True) * ng
    rand = rng.normal(size=refl.shape)
    side = np.sign((refl * ng).sum(1))[:, None]
    rand = rand * np.where((rand * ng).sum(1, keepdims=True) * side > 0, 1.0, -1.0)
    rand /= np.linalg.norm(rand, axis=1, keepdims=True)
    for out in (refl, rand, -refl, -rand):  # reflected, shadow-ray like, and refracted through
        o2 = np.array([offset_origin(tuple(pp), tuple(nn), tuple(oo)) for pp, nn, oo in zip(p, ng, out)])
        again = acc.intersect(_queue(o2, out), len(out))[0]
        assert (again >= 0).mean() <= 1e-4
