"""Prism's Embree layer against embreex's Python API on the same random rays: the same hits, the same
primitive ids, the same distances and barycentrics, the same occlusion; the record layout as Embree 4
declares it; Embree's errors as messages."""

import numpy as np
import pytest

from engine.tracer.embree import library
from engine.tracer.embree.errors import EmbreeError
from engine.tracer.embree.layout import (GEOM_ID, PRIM_ID, RAY_HIT_BYTES, RAY_HIT_DTYPE, TFAR, U, new_ray_hit_record)
from engine.tracer.embree.queries import RayCaster, closest_hits, occlusion
from engine.tracer.embree.scene import Scene, TriangleGeometry
from engine.tracer.state import HitRecord, RayQueue


def _soup(seed=7, vertices=3000, triangles=1000):
    rng = np.random.default_rng(seed)
    v = rng.random((vertices, 3)).astype(np.float32)
    t = rng.integers(0, vertices, (triangles, 3)).astype(np.int32)
    return v, t


def _rays(n, seed=11):
    rng = np.random.default_rng(seed)
    origin = (rng.random((n, 3)) * 2.0 - 0.5).astype(np.float32)
    direction = rng.normal(size=(n, 3)).astype(np.float32)
    tmax = rng.uniform(0.05, 1.5, n).astype(np.float32)
    return origin, direction, tmax


def _queue(origin, direction, tmax):
    return RayQueue(np.arange(len(origin), dtype=np.int32), origin, direction, tmax, np.full(len(origin), 0.5))


def _hits(n):
    return HitRecord(np.empty(n, np.int32), np.empty(n, np.float32), np.empty(n, np.float32), np.empty(n, np.float32))


def _embreex_scene(v, t):
    from embreex import rtcore_scene
    from embreex.mesh_construction import TriangleMesh

    scene = rtcore_scene.EmbreeScene()
    TriangleMesh(scene, v, t)
    return scene


def test_record_layout_is_embree4s():
    # RTCRay: org, tnear, dir, time, tfar, mask, id, flags (48 bytes); RTCHit from byte 48, 16-aligned
    assert RAY_HIT_DTYPE.itemsize == RAY_HIT_BYTES == 96
    assert (TFAR, U, PRIM_ID, GEOM_ID) == (8, 15, 17, 18)
    words, ids = new_ray_hit_record()
    assert words.ctypes.data % 16 == 0 and words.ctypes.data == ids.ctypes.data and words.size == 24


def test_closest_hits_match_embreex_ray_for_ray():
    v, t = _soup()
    origin, direction, tmax = _rays(20000)
    ours = Scene([TriangleGeometry(v, t)])
    caster = RayCaster(ours.handle, *new_ray_hit_record())
    hit = _hits(len(origin))
    closest_hits(caster, _queue(origin, direction, tmax), len(origin), False, hit)
    theirs = _embreex_scene(v, t).run(origin, direction, output=1)
    assert 0.1 < (hit[0] >= 0).mean() < 0.9  # both hits and misses are exercised
    np.testing.assert_array_equal(hit[0], theirs["primID"])
    found = hit[0] >= 0
    np.testing.assert_array_equal(hit[1][found], theirs["tfar"][found])
    np.testing.assert_array_equal(hit[2][found], theirs["u"][found])
    np.testing.assert_array_equal(hit[3][found], theirs["v"][found])


def test_bounded_hits_and_occlusion_match_embreex():
    v, t = _soup(seed=3)
    origin, direction, tmax = _rays(20000, seed=5)
    ours = Scene([TriangleGeometry(v, t)])
    caster = RayCaster(ours.handle, *new_ray_hit_record())
    hit = _hits(len(origin))
    closest_hits(caster, _queue(origin, direction, tmax), len(origin), True, hit)
    embreex = _embreex_scene(v, t)
    theirs = embreex.run(origin, direction, dists=tmax.copy(), output=1)
    np.testing.assert_array_equal(hit[0], theirs["primID"])
    occluded = np.empty(len(origin), np.int32)
    occlusion(caster, _queue(origin, direction, tmax), len(origin), occluded)
    expected = embreex.run(origin, direction, dists=tmax.copy(), query="OCCLUDED")
    assert 0.1 < (occluded == 0).mean() < 0.9
    np.testing.assert_array_equal(occluded, expected)
    # occluded exactly where a bounded closest hit exists
    np.testing.assert_array_equal(occluded == 0, hit[0] >= 0)


def test_an_empty_scene_misses_everything():
    origin, direction, tmax = _rays(100)
    ours = Scene([])
    caster = RayCaster(ours.handle, *new_ray_hit_record())
    hit = _hits(100)
    closest_hits(caster, _queue(origin, direction, tmax), 100, False, hit)
    assert (hit[0] == -1).all()
    occluded = np.empty(100, np.int32)
    occlusion(caster, _queue(origin, direction, tmax), 100, occluded)
    assert (occluded == -1).all()


def test_time_steps_interpolate_linearly_by_ray_time():
    # a unit square at z = 0 (time 0) moving to z = 1 (time 1): a ray down from z = 2 hits at t = 2 - time
    square = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
    moved = square + np.array([0, 0, 1], np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]])
    scene = Scene([TriangleGeometry([square, moved], triangles)])
    from engine.tracer.embree.queries import closest_hit
    from numba import njit

    @njit
    def at(caster, time):
        return closest_hit(caster, 0.1, 0.2, 2.0, 0.0, 0.0, -1.0, np.float32(np.inf), time)

    caster = RayCaster(scene.handle, *new_ray_hit_record())
    for time in (0.0, 0.25, 1.0):
        triangle, t, _, _ = at(caster, np.float32(time))
        assert triangle in (0, 1) and t == pytest.approx(2.0 - time, abs=1e-6)


def test_bad_geometry_is_a_clear_error():
    v, t = _soup()
    with pytest.raises(EmbreeError, match="vertex that does not exist"):
        TriangleGeometry(v, t + 5000)
    with pytest.raises(EmbreeError, match=r"shape \[T, 3\]"):
        TriangleGeometry(v, t[:, :2])


def test_embree_errors_name_the_call_and_embrees_reason():
    from engine.tracer.embree.device import shared_device

    device = shared_device()
    device.library.rtcNewGeometry(device.handle, 9999)  # an unknown geometry type
    with pytest.raises(EmbreeError, match=r"Embree failed to test a call \(.*invalid geometry type\)"):
        device.check("test a call")
    device.check("see the error cleared")  # reading the error clears it


def test_the_library_is_the_one_embreex_ships():
    paths = library.candidate_paths()
    assert paths and "embree4" in paths[0].name
