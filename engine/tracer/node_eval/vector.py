"""Blender's vector nodes as scalar kernel code: Mapping, Vector Rotate, and the normal perturbations
of Normal Map and Bump (the geometry they need comes from ``materials.hit_inputs``)."""

from __future__ import annotations

import math

from ..jit import kernel
from .math import safe_divide


@kernel
def euler_rotate(r, v, transpose):
    """R v (or Rᵀ v) for Blender's XYZ Euler angles ``r`` (radians): R = Rz Ry Rx."""
    cx, cy, cz = math.cos(r[0]), math.cos(r[1]), math.cos(r[2])
    sx, sy, sz = math.sin(r[0]), math.sin(r[1]), math.sin(r[2])
    m00, m01, m02 = cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz
    m10, m11, m12 = cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz
    m20, m21, m22 = -sy, cy * sx, cy * cx
    if transpose:
        return (m00 * v[0] + m10 * v[1] + m20 * v[2], m01 * v[0] + m11 * v[1] + m21 * v[2],
                m02 * v[0] + m12 * v[1] + m22 * v[2])
    return (m00 * v[0] + m01 * v[1] + m02 * v[2], m10 * v[0] + m11 * v[1] + m12 * v[2],
            m20 * v[0] + m21 * v[1] + m22 * v[2])


@kernel
def _normalized(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if n != 0.0:
        return (v[0] / n, v[1] / n, v[2] / n)
    return v


@kernel
def mapping(mode, v, location, rotation, scale):
    """Blender's Mapping node, ``MAPPING_TYPES[mode]``: Point, Texture (the inverse), Vector, Normal."""
    if mode == 0:
        r = euler_rotate(rotation, (v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]), False)
        return (r[0] + location[0], r[1] + location[1], r[2] + location[2])
    if mode == 1:
        r = euler_rotate(rotation, (v[0] - location[0], v[1] - location[1], v[2] - location[2]), True)
        return (safe_divide(r[0], scale[0]), safe_divide(r[1], scale[1]), safe_divide(r[2], scale[2]))
    if mode == 2:
        return euler_rotate(rotation, (v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]), False)
    return _normalized(euler_rotate(rotation, (safe_divide(v[0], scale[0]), safe_divide(v[1], scale[1]),
                                               safe_divide(v[2], scale[2])), False))


@kernel
def rotate_around_axis(p, axis, angle):
    c = math.cos(angle)
    s = math.sin(angle)
    x, y, z = axis
    return ((c + (1 - c) * x * x) * p[0] + ((1 - c) * x * y - z * s) * p[1] + ((1 - c) * x * z + y * s) * p[2],
            ((1 - c) * x * y + z * s) * p[0] + (c + (1 - c) * y * y) * p[1] + ((1 - c) * y * z - x * s) * p[2],
            ((1 - c) * x * z - y * s) * p[0] + ((1 - c) * y * z + x * s) * p[1] + (c + (1 - c) * z * z) * p[2])


@kernel
def vector_rotate(mode, v, center, axis, angle, rotation, invert):
    """Blender's Vector Rotate node, ``ROTATE_TYPES[mode]``, about ``center``."""
    d = (v[0] - center[0], v[1] - center[1], v[2] - center[2])
    if mode == 4:
        r = euler_rotate(rotation, d, invert)
        return (r[0] + center[0], r[1] + center[1], r[2] + center[2])
    if mode == 1:
        axis = (1.0, 0.0, 0.0)
    elif mode == 2:
        axis = (0.0, 1.0, 0.0)
    elif mode == 3:
        axis = (0.0, 0.0, 1.0)
    length = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    if length == 0.0:
        return v
    if invert:
        angle = -angle
    r = rotate_around_axis(d, (axis[0] / length, axis[1] / length, axis[2] / length), angle)
    return (r[0] + center[0], r[1] + center[1], r[2] + center[2])


@kernel
def bump_normal(normal, dpdx, dpdy, h_c, h_x, h_y, strength, distance):
    """The normal of a surface displaced by height h along ``normal``, from h at the point (``h_c``) and
    at the point moved by ``dpdx`` and ``dpdy`` (small steps in the surface): the cross product of the
    displaced steps, N' ∝ |det| N - distance sign(det) (Δh_x R_x + Δh_y R_y), blended with ``normal`` by
    ``strength`` (Blender's Bump node)."""
    rx = (dpdy[1] * normal[2] - dpdy[2] * normal[1], dpdy[2] * normal[0] - dpdy[0] * normal[2],
          dpdy[0] * normal[1] - dpdy[1] * normal[0])
    ry = (normal[1] * dpdx[2] - normal[2] * dpdx[1], normal[2] * dpdx[0] - normal[0] * dpdx[2],
          normal[0] * dpdx[1] - normal[1] * dpdx[0])
    det = dpdx[0] * rx[0] + dpdx[1] * rx[1] + dpdx[2] * rx[2]
    dx = h_x - h_c
    dy = h_y - h_c
    s = -distance * (1.0 if det > 0.0 else (-1.0 if det < 0.0 else 0.0))
    a = abs(det)
    out = (a * normal[0] + s * (dx * rx[0] + dy * ry[0]), a * normal[1] + s * (dx * rx[1] + dy * ry[1]),
           a * normal[2] + s * (dx * rx[2] + dy * ry[2]))
    n = math.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2])
    if not (n > 0.0 and math.isfinite(n)):
        return normal
    strength = max(strength, 0.0)
    out = (strength * out[0] / n + (1.0 - strength) * normal[0], strength * out[1] / n + (1.0 - strength) * normal[1],
           strength * out[2] / n + (1.0 - strength) * normal[2])
    return _normalized(out)


@kernel
def tangent_normal_map(colour, strength, normal, tangent, sign):
    """Blender's Normal Map node in tangent space: the map's colour (0-1 per axis) in the frame of the
    interpolated (unnormalised) ``normal`` and UV ``tangent`` with bitangent sign × (normal × tangent)."""
    x = 2.0 * (colour[0] - 0.5) * strength
    y = 2.0 * (colour[1] - 0.5) * strength
    z = 2.0 * (colour[2] - 0.5)
    z = 1.0 + (z - 1.0) * min(max(strength, 0.0), 1.0)
    bx = sign * (normal[1] * tangent[2] - normal[2] * tangent[1])
    by = sign * (normal[2] * tangent[0] - normal[0] * tangent[2])
    bz = sign * (normal[0] * tangent[1] - normal[1] * tangent[0])
    return _normalized((x * tangent[0] + y * bx + z * normal[0], x * tangent[1] + y * by + z * normal[1],
                        x * tangent[2] + y * bz + z * normal[2]))
