"""Sphere points through Prism's Embree layer against the analytic ray-sphere intersection: the same
sphere (row), distance and outward normal, for random rays from outside and inside the spheres, in a
scene that also holds a triangle (rows of spheres follow the triangles)."""

from collections import namedtuple

import numpy as np
import pytest

from engine.tracer.embree.errors import EmbreeError
from engine.tracer.embree.layout import new_ray_hit_record
from engine.tracer.embree.queries import RayCaster, closest_hits, occlusion
from engine.tracer.embree.scene import Scene, TriangleGeometry
from engine.tracer.embree.spheres import SphereGeometry
from engine.tracer.octahedral import decode, encode
from engine.tracer.spheres import sphere_surface
from engine.tracer.state import HitRecord, RayQueue

#: What ``spheres.sphere_surface`` reads of a ``geometry.Geometry``.
SphereTables = namedtuple("SphereTables", "spheres sphere_motion")

TRIANGLE = np.array([[-4.0, -4.0, -3.0], [4.0, -4.0, -3.0], [0.0, 4.0, -3.0]])


def _spheres(seed=2, count=12):
    rng = np.random.default_rng(seed)
    centres = rng.uniform(-1.5, 1.5, (count, 3))
    radii = rng.uniform(0.05, 0.5, count)
    return np.column_stack([centres, radii]).astype(np.float32)


def _analytic(points, origin, direction, tmax):
    """(row: -1 miss, 0 the triangle, 1 + s sphere s; t; unit normal; margin) in float64: the nearest
    hit in (0, tmax), and how far the decision is from a tie or a grazing ray (for excluding those)."""
    o = origin.astype(np.float64)
    d = direction.astype(np.float64)
    c = points[:, :3].astype(np.float64)
    r = points[:, 3].astype(np.float64)
    oc = o[:, None, :] - c[None]
    a = np.einsum("ij,ij->i", d, d)[:, None]
    b = np.einsum("ijk,ik->ij", oc, d)
    q = np.einsum("ijk,ijk->ij", oc, oc) - r[None] ** 2
    disc = b * b - a * q
    root = np.sqrt(np.maximum(disc, 0.0))
    t0, t1 = (-b - root) / a, (-b + root) / a
    t_sphere = np.where(disc > 0, np.where(t0 > 0, t0, np.where(t1 > 0, t1, np.inf)), np.inf)
    # the triangle (Moller-Trumbore)
    v0, e1, e2 = TRIANGLE[0], TRIANGLE[1] - TRIANGLE[0], TRIANGLE[2] - TRIANGLE[0]
    p = np.cross(d, e2)
    det = p @ e1
    s = o - v0
    u = np.einsum("ij,ij->i", s, p) / det
    qv = np.cross(s, e1)
    v = np.einsum("ij,ij->i", d, qv) / det
    t_tri = (qv @ e2) / det
    inside = (u >= 0) & (v >= 0) & (u + v <= 1) & (t_tri > 0)
    t_all = np.column_stack([np.where(inside, t_tri, np.inf), t_sphere])
    t_all[t_all >= tmax[:, None]] = np.inf
    row = np.argmin(t_all, axis=1)
    t = t_all[np.arange(len(o)), row]
    ordered = np.sort(t_all, axis=1)
    with np.errstate(invalid="ignore"):
        tie = np.where(np.isfinite(ordered[:, 1]), (ordered[:, 1] - ordered[:, 0]) / np.maximum(ordered[:, 0], 1e-9),
                       np.inf)
    graze = np.min(np.where(disc > 0, disc / (a * r[None] ** 2), np.inf), axis=1)
    edge = np.where(t_tri > 0, np.abs(np.column_stack([u, v, 1 - u - v])).min(axis=1), np.inf)
    margin = np.minimum.reduce([tie, graze, edge])
    row = np.where(np.isfinite(t), row, -1)
    hit_point = o + t[:, None] * d
    sphere = np.maximum(row - 1, 0)
    normal = (hit_point - c[sphere]) / r[sphere][:, None]
    return row, t, normal, margin


def _rays(n, seed=5):
    rng = np.random.default_rng(seed)
    origin = rng.uniform(-2.5, 2.5, (n, 3)).astype(np.float32)
    direction = (rng.normal(size=(n, 3)) * rng.uniform(0.5, 2.0, (n, 1))).astype(np.float32)  # not unit
    tmax = np.full(n, 1e30, np.float32)
    return origin, direction, tmax


def _trace(scene, origin, direction, tmax, sphere_geometry, first_sphere, time=None):
    caster = RayCaster(scene.handle, *new_ray_hit_record(), sphere_geometry=sphere_geometry, first_sphere=first_sphere)
    n = len(origin)
    hits = HitRecord(np.empty(n, np.int32), np.empty(n, np.float32), np.empty(n, np.float32), np.empty(n, np.float32))
    queue = RayQueue(np.arange(n, dtype=np.int32), origin, direction, tmax, np.full(n, 0.5) if time is None else time)
    closest_hits(caster, queue, n, False, hits)
    blocked = np.empty(n, np.int32)
    occlusion(caster, queue, n, blocked)
    return hits, blocked


def test_sphere_hits_match_the_analytic_intersection():
    points = _spheres()
    scene = Scene([TriangleGeometry(TRIANGLE.astype(np.float32), np.array([[0, 1, 2]])), SphereGeometry(points)])
    origin, direction, tmax = _rays(20000)
    hits, blocked = _trace(scene, origin, direction, tmax, sphere_geometry=1, first_sphere=1)
    row, t, normal, margin = _analytic(points, origin, direction, tmax)
    clear = margin > 1e-3
    assert clear.mean() > 0.95
    on_sphere = clear & (row >= 1)
    assert on_sphere.sum() > 1000 and (clear & (row == 0)).sum() > 500 and (clear & (row < 0)).sum() > 500
    np.testing.assert_array_equal(hits.triangle[clear], row[clear])
    np.testing.assert_allclose(hits.t[clear & (row >= 0)], t[clear & (row >= 0)], rtol=2e-5, atol=1e-6)
    decoded = np.array([decode(float(u), float(v)) for u, v in zip(hits.u[on_sphere], hits.v[on_sphere])])
    error = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", decoded, normal[on_sphere]), -1, 1)))
    assert error.max() < 0.05, error.max()  # degrees; float32 Ng of spheres up to 0.5 m seen from 4 m
    # occlusion sees the spheres too (-1 free, 0 blocked)
    np.testing.assert_array_equal(blocked[clear], np.where(row[clear] >= 0, 0, -1))


def test_moving_spheres_are_met_where_they_stand_at_each_rays_time():
    """The spheres and the triangle at 3 time steps, moving 0.8 m in a straight line over the shutter (the middle
    step the frame's): a ray at time τ meets them moved by (τ - 1/2) of the travel (the analytic scene, with the ray
    moved back instead), and ``sphere_surface`` at τ rebuilds the point where the ray met a sphere."""
    points = _spheres()
    travel = np.array([0.5, -0.3, 0.55])
    fractions = (-0.5, 0.0, 0.5)
    motion = np.stack([points + np.r_[travel * f, 0.0] for f in fractions]).astype(np.float32)
    triangle = [(TRIANGLE + travel * f).astype(np.float32) for f in fractions]
    scene = Scene([TriangleGeometry(triangle, np.array([[0, 1, 2]])), SphereGeometry(list(motion))])
    origin, direction, tmax = _rays(20000, seed=6)
    time = np.random.default_rng(4).uniform(0.0, 1.0, len(origin))
    moved_back = (origin - (time - 0.5)[:, None] * travel).astype(np.float32)
    hits, blocked = _trace(scene, origin, direction, tmax, 1, 1, time)
    row, t, normal, margin = _analytic(points, moved_back, direction, tmax)
    clear = margin > 1e-3
    on_sphere = clear & (row >= 1)
    assert on_sphere.sum() > 1000 and (clear & (row == 0)).sum() > 500 and (clear & (row < 0)).sum() > 500
    np.testing.assert_array_equal(hits.triangle[clear], row[clear])
    np.testing.assert_allclose(hits.t[clear & (row >= 0)], t[clear & (row >= 0)], rtol=2e-5, atol=1e-6)
    np.testing.assert_array_equal(blocked[clear], np.where(row[clear] >= 0, 0, -1))
    tables = SphereTables(motion[1], motion)
    rebuilt = np.array([sphere_surface(tables, int(r) - 1, float(u), float(v), float(tau))[0] for r, u, v, tau in
                        zip(hits.triangle[on_sphere], hits.u[on_sphere], hits.v[on_sphere], time[on_sphere])])
    hit_point = origin[on_sphere] + t[on_sphere, None] * direction[on_sphere].astype(np.float64)
    assert np.linalg.norm(rebuilt - hit_point, axis=1).max() < 1e-4
    # at the frame's time (-1) the frame's spheres, whatever the steps
    frame = sphere_surface(tables, 0, *encode(0.0, 0.0, 1.0), -1.0)[0]
    np.testing.assert_allclose(frame, points[0, :3] + [0.0, 0.0, points[0, 3]], atol=1e-6)


def test_a_growing_sphere_is_met_at_its_radius_at_each_rays_time():
    """A sphere whose radius grows from 0 to 0.6 m over the shutter (Embree interpolates it with the centre): rays
    from 3 m away aimed at its centre meet it at 3 - r(τ)."""
    motion = np.array([[[0.0, 0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0, 0.3]], [[0.0, 0.0, 0.0, 0.6]]], np.float32)
    scene = Scene([SphereGeometry(list(motion))])
    rng = np.random.default_rng(2)
    n = 2000
    toward = rng.normal(size=(n, 3))
    toward /= np.linalg.norm(toward, axis=1, keepdims=True)
    time = rng.uniform(0.02, 1.0, n)
    hits, _ = _trace(scene, (-3.0 * toward).astype(np.float32), toward.astype(np.float32),
                     np.full(n, 1e30, np.float32), 0, 0, time)
    assert (hits.triangle == 0).all()
    np.testing.assert_allclose(hits.t, 3.0 - 0.6 * time, atol=2e-5)


def test_rays_leaving_a_sphere_from_its_offset_surface_do_not_hit_it_again():
    points = np.array([[0.3, -0.2, 5.0, 0.01]], np.float32)  # 1 cm, 5 m from the origin
    scene = Scene([SphereGeometry(points)])
    rng = np.random.default_rng(1)
    n = 5000
    normal = rng.normal(size=(n, 3))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    p = points[0, :3].astype(np.float64) + points[0, 3] * normal
    eps = 4e-6 * np.abs(p).max(axis=1, keepdims=True) + 1e-7  # geometry.offset_origin
    outward = rng.normal(size=(n, 3))
    outward *= np.sign(np.einsum("ij,ij->i", outward, normal))[:, None]
    hits, _ = _trace(scene, (p + eps * normal).astype(np.float32), outward.astype(np.float32),
                     np.full(n, 1e30, np.float32), 0, 0)
    assert (hits.triangle == -1).all()
    inward = -outward
    hits, _ = _trace(scene, (p - eps * normal).astype(np.float32), inward.astype(np.float32),
                     np.full(n, 1e30, np.float32), 0, 0)
    assert (hits.triangle == 0).all()  # the far side, from inside
    assert (hits.t > 1e-4).all()


def test_octahedral_round_trip():
    rng = np.random.default_rng(3)
    for x, y, z in rng.normal(size=(2000, 3)):
        u, v = encode(x, y, z)
        back = np.array(decode(float(np.float32(u)), float(np.float32(v))))
        assert np.linalg.norm(back - np.array([x, y, z]) / np.linalg.norm([x, y, z])) < 1e-6


def test_bad_spheres_are_refused():
    with pytest.raises(EmbreeError, match="positive"):
        SphereGeometry(np.array([[0, 0, 0, 0.0]], np.float32))
    with pytest.raises(EmbreeError, match="shape"):
        SphereGeometry(np.zeros((3, 3), np.float32))
    with pytest.raises(EmbreeError, match="every time step"):
        SphereGeometry([np.ones((2, 4), np.float32), np.ones((3, 4), np.float32)])
    with pytest.raises(EmbreeError, match="positive"):  # a radius below 0 at some step
        SphereGeometry([np.ones((1, 4), np.float32), -np.ones((1, 4), np.float32)])
