"""Embree queries: closest hits, occlusion, rejected rays, dropped triangles, self-intersection."""

import numpy as np
import pytest

from engine.tracer.accel import Accel
from engine.tracer.path_state import TriangleData, offset_origin
from engine.tracer.scene import Camera, Material, Scene

from .tracer_scenes import quad


def test_closest_hit_and_occlusion():
    v1, t1 = quad((0, 0, 0), (1, 0, 0), (0, 1, 0))
    v2, t2 = quad((0, 0, -1), (1, 0, 0), (0, 1, 0))
    acc = Accel(np.vstack([v1, v2]), np.vstack([t1, t2 + 4]), threads=2)
    o = np.array([[0.2, 0.3, 2.0], [0.5, 0.5, -0.5], [5.0, 5.0, 1.0]])
    d = np.array([[0, 0, -1.0], [0, 0, -1.0], [0, 0, -1.0]])
    tri, t, u, v = acc.intersect(o, d)
    assert tri[0] in (0, 1) and t[0] == pytest.approx(2.0)
    assert tri[1] in (2, 3) and t[1] == pytest.approx(0.5)
    assert tri[2] == -1 and np.isinf(t[2])
    assert acc.occluded(o, d, np.array([1.9, 0.6, 10.0])).tolist() == [False, True, False]
    assert acc.occluded(o, d, np.array([2.1, 0.4, 10.0])).tolist() == [True, False, False]


def test_non_finite_rays_are_not_sent_and_zero_area_triangles_dropped():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 2, 2]], np.float32)
    acc = Accel(v, np.array([[0, 1, 2], [3, 3, 3], [0, 1, 1]]), threads=1)
    assert acc.dropped_triangles == 2
    o = np.array([[0.1, 0.1, 1.0], [np.nan, 0, 1], [0.1, 0.1, 1.0]])
    d = np.array([[0, 0, -1.0], [0, 0, -1.0], [np.inf, 0, -1]])
    tri, t, _, _ = acc.intersect(o, d)
    assert tri.tolist() == [0, -2, -2] and acc.rejected_rays == 2  # -2: not sent
    assert acc.occluded(o, d, np.array([2.0, 2.0, 2.0])).tolist() == [True, True, True]


def test_many_rays_split_over_threads_match_single_thread():
    rng = np.random.default_rng(0)
    v, t = quad((0, 0, 0), (1, 0, 0), (0, 1, 0))
    n = 100_000
    o = np.column_stack([rng.uniform(-2, 2, (n, 2)), np.ones(n)])
    d = np.tile([0.0, 0.0, -1.0], (n, 1))
    a = Accel(v, t, threads=2).intersect(o, d)
    b = Accel(v, t, threads=1).intersect(o, d)
    assert all(np.array_equal(x, y) for x, y in zip(a, b))
    assert np.array_equal(a[0] >= 0, (np.abs(o[:, :2]) <= 1).all(1))


@pytest.mark.parametrize("scale", [1.0, 1e4])
def test_reflected_rays_do_not_rehit_their_surface(scale):
    """Secondary rays off a tilted plane far from the origin never hit the plane again."""
    rng = np.random.default_rng(1)
    center = np.array([1.0, -0.7, 0.4]) * scale
    u = np.array([1.0, 0.2, 0.3]) * 0.5 * scale
    w = np.cross(u, [0.1, 0.3, 1.0])
    w *= np.linalg.norm(u) / np.linalg.norm(w)
    v, t = quad(center, u, w)
    scene = Scene(vertices=v.astype(np.float32), triangles=t.astype(np.int32), triangle_material=np.zeros(2, np.int32),
                  materials=[Material("m")], camera=Camera("c", np.eye(4), (1, 1)))
    acc = Accel(scene.vertices, scene.triangles)
    data = TriangleData(scene)
    n = 200_000
    normal = data.normal[0].astype(np.float64)
    targets = center + rng.uniform(-0.9, 0.9, (n, 1)) * u + rng.uniform(-0.9, 0.9, (n, 1)) * w
    origins = targets + normal * scale * rng.uniform(0.1, 1.0, (n, 1)) + rng.normal(size=(n, 3)) * 0.1 * scale
    d = targets - origins
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    tri, tt, bu, bv = acc.intersect(origins, d)
    hit = tri >= 0
    p, ng, _ = data.surface(tri[hit], bu[hit], bv[hit])
    dh = d[hit]
    # mirror reflection and a random direction on the same side (shadow-ray like)
    refl = dh - 2 * (dh * ng).sum(1, keepdims=True) * ng
    rand = rng.normal(size=refl.shape)
    rand *= np.sign((rand * refl).sum(1))[:, None] * np.sign((refl * ng).sum(1))[:, None]
    side = np.sign((refl * ng).sum(1))[:, None]
    rand = rand * np.where((rand * ng).sum(1, keepdims=True) * side > 0, 1.0, -1.0)
    for out in (refl, rand / np.linalg.norm(rand, axis=1, keepdims=True)):
        o2 = offset_origin(p, ng, out)
        again, _, _, _ = acc.intersect(o2, out)
        assert (again >= 0).mean() <= 1e-4
        # and rays continuing through the surface (refraction) do not get stuck on it either
        through = offset_origin(p, ng, -out)
        again, _, _, _ = acc.intersect(through, -out)
        assert (again >= 0).mean() <= 1e-4
