"""Ray queries from compiled code: one ray (``closest_hit``, ``is_occluded``) and whole queues
(``closest_hits``, ``occlusion``).

Kernels call Embree's ``rtcIntersect1`` / ``rtcOccluded1`` by symbol (``library`` registers them), on
a per-thread ``RTCRayHit`` record (``layout.new_ray_hit_record``) passed as its float32 and uint32
views. Rays start at distance 0 (callers offset secondary origins, as with embreex) and carry their
path's ray time (``RayQueue.time``, by path), which geometry with several time steps interpolates by.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba.core import types

from ..curves import hit_code
from ..jit import inlined, kernel
from ..octahedral import encode
from . import library
from .layout import ALL_MASK, DIR_X, FLAGS, GEOM_ID, INST_ID, INVALID_ID, MASK, NG_X, ORG_X, PRIM_ID, RAY_ID, TFAR, \
    TIME, TNEAR, U, V

#: What a compiled loop traces against: ``scene`` the committed ``RTCScene`` handle (``scene.Scene.handle``),
#: this thread's ``RTCRayHit`` record as its float32 ``words`` and uint32 ``ids`` views, and how Embree's
#: (geometry, primitive) ids map to rows of the render's triangles: ``moving_geometry`` the geometry id of
#: the moving triangles (-1: one geometry whose primitive ids are the rows), ``triangle_of`` int32 (the
#: static geometry's rows, then the moving one's) and ``first_moving`` (where the moving rows start in it);
#: ``sphere_geometry`` the geometry id of the sphere points (-1: none) and ``first_sphere`` the row of its
#: sphere 0 (spheres follow the triangles: row = ``first_sphere`` + primitive id); ``curve_geometry`` the
#: geometry id of the curve segments (-1: none), ``first_curve`` the row of its segment 0 (after the spheres)
#: and ``curves`` / ``curve_segments`` / ``curve_motion`` their control points, segments and control points at
#: the shutter's time steps (``Geometry.curves``, ``curve_motion``), which a curve hit's code is computed from.
RayCaster = namedtuple("RayCaster", "scene words ids moving_geometry triangle_of first_moving sphere_geometry "
                       "first_sphere curve_geometry first_curve curves curve_segments curve_motion",
                       defaults=(-1, np.zeros(1, np.int32), 0, -1, 0, -1, 0, np.zeros((0, 4), np.float32),
                                 np.zeros(0, np.int32), np.zeros((0, 0, 4), np.float32)))

library.load()  # before any kernel below is compiled or loaded: they link to its symbols by name

# void rtcIntersect1(RTCScene, RTCRayHit*, RTCIntersectArguments*) and rtcOccluded1(RTCScene, RTCRay*,
# RTCOccludedArguments*): pointers passed as machine words (same registers on every supported ABI);
# null arguments select Embree's defaults.
_rtc_intersect1 = types.ExternalFunction("rtcIntersect1", types.void(types.uintp, types.uintp, types.uintp))
_rtc_occluded1 = types.ExternalFunction("rtcOccluded1", types.void(types.uintp, types.uintp, types.uintp))


@inlined
def _set_ray(words, ids, ox, oy, oz, dx, dy, dz, tmax, time):
    words[ORG_X] = ox
    words[ORG_X + 1] = oy
    words[ORG_X + 2] = oz
    words[TNEAR] = 0.0
    words[DIR_X] = dx
    words[DIR_X + 1] = dy
    words[DIR_X + 2] = dz
    words[TIME] = time
    words[TFAR] = tmax
    ids[MASK] = ALL_MASK
    ids[RAY_ID] = 0
    ids[FLAGS] = 0


@inlined
def closest_hit(caster, ox, oy, oz, dx, dy, dz, tmax, time):
    """Closest triangle or sphere along the ray before ``tmax`` in ``caster.scene`` at ray time ``time``
    (0..1): (row, or -1 for a miss; t; u; v). On a miss t is ``tmax``. Rows past the triangles are
    spheres; their (u, v) is the octahedral code of the outward normal (``octahedral.encode``). Rows past
    the spheres are curve segments; their u is the curve parameter, v the normal's angle around the
    tangent (``curves.hit_code``)."""
    words = caster.words
    ids = caster.ids
    _set_ray(words, ids, ox, oy, oz, dx, dy, dz, tmax, time)
    ids[GEOM_ID] = INVALID_ID
    ids[PRIM_ID] = INVALID_ID
    ids[INST_ID] = INVALID_ID
    _rtc_intersect1(caster.scene, words.ctypes.data, 0)
    if ids[GEOM_ID] == INVALID_ID:
        return -1, words[TFAR], np.float32(0.0), np.float32(0.0)
    if np.int64(ids[GEOM_ID]) == caster.sphere_geometry:
        nu, nv = encode(float(words[NG_X]), float(words[NG_X + 1]), float(words[NG_X + 2]))
        return (np.int32(caster.first_sphere + np.int64(ids[PRIM_ID])), words[TFAR], np.float32(nu),
                np.float32(nv))
    if np.int64(ids[GEOM_ID]) == caster.curve_geometry:
        c = np.int64(ids[PRIM_ID])
        angle = hit_code(caster, c, float(words[U]), float(words[NG_X]), float(words[NG_X + 1]),
                         float(words[NG_X + 2]), time)
        return np.int32(caster.first_curve + c), words[TFAR], words[U], np.float32(angle)
    if caster.moving_geometry < 0:
        return np.int32(ids[PRIM_ID]), words[TFAR], words[U], words[V]
    row = np.int64(ids[PRIM_ID])
    if np.int64(ids[GEOM_ID]) == caster.moving_geometry:
        row += caster.first_moving
    return np.int32(caster.triangle_of[row]), words[TFAR], words[U], words[V]


@inlined
def is_occluded(scene, words, ids, ox, oy, oz, dx, dy, dz, tmax, time):
    """True if anything in ``scene`` lies on the ray between 0 and ``tmax``."""
    _set_ray(words, ids, ox, oy, oz, dx, dy, dz, tmax, time)
    _rtc_occluded1(scene, words.ctypes.data, 0)
    return words[TFAR] < 0.0  # Embree sets tfar to -inf when it finds an occluder


@kernel
def closest_hits(caster, rays, count, bounded, hits):
    """Closest hits of rays ``0 .. count`` of ``rays`` (a ``state.RayQueue``: float32 ``origin`` /
    ``direction`` [n, 3], ``tmax`` [n]) into ``hits`` (a ``state.HitRecord``: ``triangle`` int32, -1 for a
    miss; ``t``, ``u``, ``v`` float32), before ``tmax`` where ``bounded``, else unbounded."""
    for j in range(count):
        limit = rays.tmax[j] if bounded else np.float32(np.inf)
        hits.triangle[j], hits.t[j], hits.u[j], hits.v[j] = closest_hit(
            caster, rays.origin[j, 0], rays.origin[j, 1], rays.origin[j, 2],
            rays.direction[j, 0], rays.direction[j, 1], rays.direction[j, 2], limit,
            np.float32(rays.time[rays.path[j]]))


@kernel
def occlusion(caster, rays, count, occluded):
    """``occluded[j]`` (int32) 0 where something lies before ``rays.tmax[j]``, -1 where ray ``j`` is free
    (embreex's convention), for rays ``0 .. count`` of a ``state.RayQueue``."""
    for j in range(count):
        blocked = is_occluded(caster.scene, caster.words, caster.ids, rays.origin[j, 0], rays.origin[j, 1],
                              rays.origin[j, 2], rays.direction[j, 0], rays.direction[j, 1], rays.direction[j, 2],
                              rays.tmax[j], np.float32(rays.time[rays.path[j]]))
        occluded[j] = 0 if blocked else -1
