"""The render's triangles, relative to the render's origin, and the hit-point maths the kernels share.

World positions are float64 (``scene.Scene``); the origin (the camera position, see ``cameras``) is
subtracted in float64 before anything becomes float32, so Embree's float32 precision is spent near the
camera: a scene moved 1e7 m from the origin renders as it does at the origin. Zero-area and non-finite triangles are dropped here
(Embree ids are then this table's rows; ``original`` maps them back for messages).

``Geometry``: ``vertices`` float32 [V, 3] (camera-relative metres), ``triangles`` int32 [T, 3],
``material`` int32 [T], ``normals`` float32 [T, 3, 3] (unit shading normals at the corners) or
[0, 3, 3] for flat shading, ``attributes`` (``SurfaceArrays``: what node materials read, empty arrays
when nothing does), ``flags`` uint8 [T] (``visibility``: the rays that see the triangle's object, and
whether it is a holdout), ``motion`` float32 [S, V, 3] (with motion blur: the vertices at S evenly spaced
times of the shutter, camera-relative; [0, 0, 3] without) and ``motion_normals`` float32 [S, T, 3, 3] (the
corner normals at those times; [0, 0, 3, 3] without, or for flat shading). A ray at time τ (0..1) sees
vertices interpolated linearly between the two steps around τ·(S-1), as Embree interpolates them.
``spheres`` float32 [S, 4] (``spheres``: the points of point clouds, camera-relative centre and radius; [0, 4]
without), ``sphere_random`` float32 [S] (each point's Point Info ▸ Random) and ``sphere_motion`` float32 [M, S, 4]
(with motion blur, the spheres at the shutter's time steps; [0, 0, 4] without): rows T .. T + S - 1 of the
render's primitives.
``curves`` float32 [P, 4] and ``curve_segments`` int32 [C] (``curves``: the control points of hair strands,
camera-relative point and radius, and the first control point of each segment; [0, 4] and [0] without) and
``curve_info`` float32 [C, 4] (each segment's Hair Info, ``curves.curve_info``) and ``curve_motion`` float32
[S, P, 4] (with motion blur, the control points at the shutter's time steps; [0, 0, 4] without):
rows T + S .. T + S + C - 1. So ``material``, ``flags`` (and ``attributes.instance`` when it is not empty)
hold T + S + C entries; the per-corner tables hold T, but for the colour attributes and UV maps, which hold
rows for the spheres (each point's colours at all three corners) and the segments (``curves.corner_rows``)
where these carry any (``_with_primitive_rows``).
``terminator`` float32 [T, 2]: each triangle's shadow terminator Geometry Offset (0 where shaded flat or without
corner normals) and Shading Offset multiplier (0: none) (``terminator``), or [0, 2] when no triangle has either.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from . import curves as hair
from .jit import inlined, kernel
from .vec3 import tangents
from .spheres import (camera_relative, camera_relative_steps, no_sphere_motion, no_spheres, point_random, rendered_rows,
                      sphere_surface)

Geometry = namedtuple("Geometry", "vertices triangles material normals attributes flags motion motion_normals spheres "
                      "sphere_random curves curve_segments curve_info curve_motion sphere_motion terminator",
                      defaults=(no_spheres(), np.zeros(0, np.float32), *hair.no_curves(), np.zeros((0, 4), np.float32),
                                hair.no_curve_motion(), no_sphere_motion(), np.zeros((0, 2), np.float32)))

#: A ``surface_at`` time that reads the positions at the frame (``Geometry.vertices``), where the light
#: table's emitters stand, instead of those at a ray time of the shutter.
FRAME_TIME = -1.0


def no_motion():
    """``Geometry.motion`` / ``motion_normals`` of a render without motion blur: empty, so kernels take
    the static path."""
    return np.zeros((0, 0, 3), np.float32), np.zeros((0, 0, 3, 3), np.float32)

#: UV maps, colour attributes and UV tangents per corner, instance of each triangle, instance rows, the
#: camera position (world = camera-relative + ``offset``) and object-space corner positions; see
#: ``scene.SurfaceAttributes``.
SurfaceArrays = namedtuple("SurfaceArrays", "uvs colors tangents instance objects offset positions")

# Secondary rays start this far (relative to the largest coordinate of the hit point) off the surface:
# ~30 float32 ulps, above Embree's float32 error.
OFFSET_RELATIVE = 4e-6
OFFSET_ABSOLUTE = 1e-7


def prepare_geometry(scene, offset):
    """(``Geometry``, original triangle index [T] int64, dropped count) for ``scene`` with ``offset``
    (the camera position, m) subtracted; the spheres of ``scene.points`` that render follow the triangles
    (``spheres.rendered_rows``), the segments of ``scene.curves`` the spheres."""
    vertices = np.asarray(scene.vertices, dtype=np.float64) - np.asarray(offset, dtype=np.float64)
    triangles = np.asarray(scene.triangles, dtype=np.int64).reshape(-1, 3)
    relative32 = vertices.astype(np.float32)
    keep = np.empty(len(triangles), dtype=np.bool_)
    _non_degenerate(relative32, triangles, keep)
    original = np.flatnonzero(keep)
    material = np.asarray(scene.triangle_material, dtype=np.int32)[original]
    normals = np.zeros((0, 3, 3), np.float32)
    if scene.corner_normals is not None and len(scene.corner_normals) == len(triangles):
        normals = np.ascontiguousarray(np.asarray(scene.corner_normals, dtype=np.float32)[original])
    from .visibility import curve_flags, sphere_flags, triangle_flags

    points = getattr(scene, "points", None)
    motion = getattr(scene, "motion", None)
    rows = rendered_rows(points)
    flags = triangle_flags(scene, original)
    attributes = surface_arrays(scene.surface, original, offset)
    if len(rows):
        material = np.concatenate([material, np.asarray(points.material, np.int32)[rows]])
        flags = np.concatenate([flags, sphere_flags(scene, rows)])
        if scene.surface is not None and scene.surface.triangle_instance is not None:
            of_sphere = (np.asarray(points.instance, np.int32)[rows] if points.instance is not None
                         else np.full(len(rows), -1, np.int32))
            attributes = attributes._replace(instance=np.concatenate([attributes.instance, of_sphere]))
    strands = getattr(scene, "curves", None)
    if hair.curve_count(strands):
        material = np.concatenate([material, np.asarray(strands.material, np.int32)])
        flags = np.concatenate([flags, curve_flags(scene)])
        if scene.surface is not None and scene.surface.triangle_instance is not None:
            of_segment = (np.asarray(strands.instance, np.int32) if strands.instance is not None
                          else np.full(len(strands), -1, np.int32))
            attributes = attributes._replace(instance=np.concatenate([attributes.instance, of_segment]))
    attributes = _with_primitive_rows(attributes, points, rows, strands)
    geometry = Geometry(np.ascontiguousarray(relative32), np.ascontiguousarray(triangles[original], dtype=np.int32),
                        np.ascontiguousarray(material), normals, attributes, np.ascontiguousarray(flags),
                        *_motion_arrays(scene, original, offset, len(normals)), camera_relative(points, rows, offset),
                        point_random(points, rows), *hair.camera_relative(strands, offset), hair.curve_info(strands),
                        hair.camera_relative_motion(strands, getattr(motion, "curves", None), offset),
                        camera_relative_steps(points, rows, getattr(motion, "points", None), offset),
                        _terminator_offsets(scene, original, len(normals)))
    return geometry, original, int(len(triangles) - len(original))


def _terminator_offsets(scene, original, smooth):
    """``Geometry.terminator`` of the render's triangles ``original`` (``smooth``: whether they carry corner
    normals, which the Geometry Offset needs)."""
    offsets = getattr(scene, "triangle_terminator", None)
    if offsets is None or len(offsets) != scene.triangle_count:
        return np.zeros((0, 2), np.float32)
    offsets = np.array(np.asarray(offsets, np.float32).reshape(-1, 2)[original])
    if not smooth:
        offsets[:, 0] = 0.0
    if not ((offsets[:, 0] > 0.0).any() or (offsets[:, 1] > 1.0).any()):
        return np.zeros((0, 2), np.float32)
    return np.ascontiguousarray(offsets)


def _with_primitive_rows(attributes, points, rows, strands):
    """``attributes`` with the colour and UV tables grown by a row per rendered sphere (``rows`` of ``points``: its
    value at all three corners) and per curve segment (``curves.corner_rows``), where either carries values."""
    sphere_colors = points.colors if points is not None and len(rows) else None
    has_curves = hair.curve_count(strands) > 0
    for table, sphere_values, curve_ends in (("colors", sphere_colors, strands.colors if has_curves else None),
                                             ("uvs", None, strands.uvs if has_curves else None)):
        corners = getattr(attributes, table)
        if not corners.shape[0] or (sphere_values is None and curve_ends is None):
            continue
        if sphere_values is None:  # points carry none: they read 0
            spheres = np.zeros((corners.shape[0], len(rows), *corners.shape[2:]), np.float32)
        else:
            spheres = np.repeat(np.asarray(sphere_values, np.float32)[:, rows, None, :], 3, axis=2)
        parts = [corners, spheres] + ([hair.corner_rows(curve_ends)] if curve_ends is not None else [])
        attributes = attributes._replace(**{table: np.ascontiguousarray(np.concatenate(parts, axis=1))})
    return attributes


def _motion_arrays(scene, original, offset, smooth):
    """(``motion``, ``motion_normals``) of ``scene.motion`` for the kept triangles ``original``."""
    motion = getattr(scene, "motion", None)
    if motion is None or motion.vertices is None:
        return no_motion()
    steps = (np.asarray(motion.vertices, np.float64) - np.asarray(offset, np.float64)).astype(np.float32)
    normals = np.zeros((0, 0, 3, 3), np.float32)
    if smooth and motion.corner_normals is not None:
        normals = np.ascontiguousarray(np.asarray(motion.corner_normals, np.float32)[:, original])
    return np.ascontiguousarray(steps), normals


def surface_arrays(surface, original, offset) -> SurfaceArrays:
    """The kernels' view of ``scene.SurfaceAttributes`` for the kept triangles ``original``, with the camera
    position ``offset`` folded into the world→object transforms."""
    offset = np.asarray(offset, dtype=np.float64)
    if surface is None:
        return SurfaceArrays(np.zeros((0, 0, 3, 2), np.float32), np.zeros((0, 0, 3, 4), np.float32),
                             np.zeros((0, 0, 3, 4), np.float32), np.zeros(0, np.int32), np.zeros((0, 27)), offset,
                             np.zeros((0, 3, 3), np.float32))

    def kept(array, corner_width):
        array = np.asarray(array, dtype=np.float32)
        if array.shape[0] == 0:
            return np.zeros((0, len(original), 3, corner_width), np.float32)
        return np.ascontiguousarray(array[:, original])

    objects = np.array(surface.instances, dtype=np.float64).reshape(-1, 27)
    if len(objects):
        linear = objects[:, :12].reshape(-1, 3, 4)
        linear[:, :, 3] += linear[:, :, :3] @ offset
        objects[:, :12] = linear.reshape(-1, 12)
    instance = np.zeros(0, np.int32)
    if surface.triangle_instance is not None:
        instance = np.ascontiguousarray(np.asarray(surface.triangle_instance, dtype=np.int32)[original])
    positions = np.asarray(surface.positions, dtype=np.float32)
    positions = np.ascontiguousarray(positions[original]) if len(positions) else np.zeros((0, 3, 3), np.float32)
    return SurfaceArrays(kept(surface.uvs, 2), kept(surface.colors, 4), kept(surface.tangents, 4), instance,
                         np.ascontiguousarray(objects), offset, positions)


@kernel
def _non_degenerate(vertices, triangles, keep):
    """``keep[t]``: triangle t has a finite, non-zero area in the float32 vertices Embree will see."""
    for t in range(triangles.shape[0]):
        a, b, c = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        e1x = float(vertices[b, 0]) - float(vertices[a, 0])
        e1y = float(vertices[b, 1]) - float(vertices[a, 1])
        e1z = float(vertices[b, 2]) - float(vertices[a, 2])
        e2x = float(vertices[c, 0]) - float(vertices[a, 0])
        e2y = float(vertices[c, 1]) - float(vertices[a, 1])
        e2z = float(vertices[c, 2]) - float(vertices[a, 2])
        nx = e1y * e2z - e1z * e2y
        ny = e1z * e2x - e1x * e2z
        nz = e1x * e2y - e1y * e2x
        area2 = nx * nx + ny * ny + nz * nz
        keep[t] = math.isfinite(area2) and area2 > 0.0


@kernel
def vertex_at(geometry, vertex, time):
    """Vertex ``vertex`` (float64 xyz) at ray time ``time`` (``FRAME_TIME``: at the frame)."""
    m = geometry.motion
    if m.shape[0] == 0 or time < 0.0:
        vs = geometry.vertices
        return float(vs[vertex, 0]), float(vs[vertex, 1]), float(vs[vertex, 2])
    x = min(max(time, 0.0), 1.0) * (m.shape[0] - 1)
    s = min(int(x), m.shape[0] - 2)
    f = x - s
    return ((1.0 - f) * float(m[s, vertex, 0]) + f * float(m[s + 1, vertex, 0]),
            (1.0 - f) * float(m[s, vertex, 1]) + f * float(m[s + 1, vertex, 1]),
            (1.0 - f) * float(m[s, vertex, 2]) + f * float(m[s + 1, vertex, 2]))


@kernel
def corner_normal(geometry, triangle, corner, time):
    """Corner ``corner``'s shading normal (not unit) at ray time ``time``."""
    m = geometry.motion_normals
    if m.shape[0] == 0 or time < 0.0:
        cn = geometry.normals[triangle]
        return float(cn[corner, 0]), float(cn[corner, 1]), float(cn[corner, 2])
    x = min(max(time, 0.0), 1.0) * (m.shape[0] - 1)
    s = min(int(x), m.shape[0] - 2)
    f = x - s
    return ((1.0 - f) * float(m[s, triangle, corner, 0]) + f * float(m[s + 1, triangle, corner, 0]),
            (1.0 - f) * float(m[s, triangle, corner, 1]) + f * float(m[s + 1, triangle, corner, 1]),
            (1.0 - f) * float(m[s, triangle, corner, 2]) + f * float(m[s + 1, triangle, corner, 2]))


@inlined
def surface_at(geometry, triangle, u, v, time):
    """(point, unit geometric normal, unit shading normal on the geometric normal's side) at
    barycentrics (u, v) of ``triangle`` (corner weights 1 - u - v, u, v) at ray time ``time`` (0..1 over
    the shutter; ``FRAME_TIME`` or no motion: the frame's vertices). Rows past the triangles are spheres,
    (u, v) then the octahedral code of the normal (``spheres``), then curve segments, (u, v) then the curve
    parameter and the normal's angle around the tangent (``curves``)."""
    if triangle >= geometry.triangles.shape[0]:
        s = triangle - geometry.triangles.shape[0]
        if s < geometry.spheres.shape[0]:
            return sphere_surface(geometry, s, u, v, time)
        return hair.curve_surface(geometry, s - geometry.spheres.shape[0], u, v, time)
    a = geometry.triangles[triangle, 0]
    b = geometry.triangles[triangle, 1]
    c = geometry.triangles[triangle, 2]
    ax, ay, az = vertex_at(geometry, a, time)
    bx, by, bz = vertex_at(geometry, b, time)
    cx, cy, cz = vertex_at(geometry, c, time)
    e1 = (bx - ax, by - ay, bz - az)
    e2 = (cx - ax, cy - ay, cz - az)
    p = (ax + u * e1[0] + v * e2[0], ay + u * e1[1] + v * e2[1], az + u * e1[2] + v * e2[2])
    nx = e1[1] * e2[2] - e1[2] * e2[1]
    ny = e1[2] * e2[0] - e1[0] * e2[2]
    nz = e1[0] * e2[1] - e1[1] * e2[0]
    n = math.sqrt(nx * nx + ny * ny + nz * nz)
    ng = (nx / n, ny / n, nz / n)
    if geometry.normals.shape[0] == 0:
        return p, ng, ng
    w = 1.0 - u - v
    n0 = corner_normal(geometry, triangle, 0, time)
    n1 = corner_normal(geometry, triangle, 1, time)
    n2 = corner_normal(geometry, triangle, 2, time)
    sx = w * n0[0] + u * n1[0] + v * n2[0]
    sy = w * n0[1] + u * n1[1] + v * n2[1]
    sz = w * n0[2] + u * n1[2] + v * n2[2]
    length = math.sqrt(sx * sx + sy * sy + sz * sz)
    if not (length > 1e-12 and math.isfinite(length)):
        return p, ng, ng
    if sx * ng[0] + sy * ng[1] + sz * ng[2] < 0.0:
        length = -length
    return p, ng, (sx / length, sy / length, sz / length)


@kernel
def offset_origin(p, ng, toward):
    """``p`` moved off its surface along ``ng`` to the side of direction ``toward``."""
    eps = OFFSET_RELATIVE * max(abs(p[0]), abs(p[1]), abs(p[2])) + OFFSET_ABSOLUTE
    if toward[0] * ng[0] + toward[1] * ng[1] + toward[2] * ng[2] < 0.0:
        eps = -eps
    return (p[0] + eps * ng[0], p[1] + eps * ng[1], p[2] + eps * ng[2])


@inlined
def hit_tangent(geometry, triangle, u, n, along_v, time):
    """A unit tangent at a hit, the direction Cycles' hair closures take as the fibre's: a curve's tangent at
    ``u`` at ray time ``time``; on a triangle d position / d barycentric u (its first edge; Cycles'
    ``sd->dPdu``), or with ``along_v`` d position / d v (its second edge, ``sd->dPdv``, what the Hair BSDF takes);
    on a sphere a tangent of its normal ``n``."""
    if triangle >= geometry.triangles.shape[0]:
        s = triangle - geometry.triangles.shape[0]
        if s >= geometry.spheres.shape[0]:
            t = hair.curve_tangent(geometry, s - geometry.spheres.shape[0], u, time)
        else:
            t = tangents(n)[0]
    else:
        a = geometry.triangles[triangle, 0]
        b = geometry.triangles[triangle, 2 if along_v else 1]
        vs = geometry.vertices
        t = (float(vs[b, 0]) - float(vs[a, 0]), float(vs[b, 1]) - float(vs[a, 1]), float(vs[b, 2]) - float(vs[a, 2]))
    size = math.sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2])
    if not size > 0.0:
        return tangents(n)[0]
    return (t[0] / size, t[1] / size, t[2] / size)


@inlined
def on_curve(geometry, triangle):
    """Whether a hit's row is a hair strand's segment."""
    return triangle >= geometry.triangles.shape[0] + geometry.spheres.shape[0]


@inlined
def leave_surface(geometry, triangle, u, p, ng, toward, time):
    """(origin, distance skipped) of a ray leaving the hit at ``p`` along unit ``toward``: ``offset_origin``, or,
    into a hair strand's tube, from just outside the tube's far wall (``curves.leave_tube``; the strand where it
    stands at the ray's ``time``)."""
    if on_curve(geometry, triangle) and toward[0] * ng[0] + toward[1] * ng[1] + toward[2] * ng[2] < 0.0:
        first_curve = geometry.triangles.shape[0] + geometry.spheres.shape[0]
        q, t = hair.leave_tube(geometry, triangle - first_curve, u, p, toward, time)
        if t > 0.0:
            return offset_origin(q, toward, toward), t
    return offset_origin(p, ng, toward), 0.0
