"""Blender's pattern textures: Checker, Gradient, Wave, Brick, Magic and White Noise, as scalar kernel
code matching Blender's definitions (coordinates nudged off exact unit values as Blender does, so edges
fall on the same side)."""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from .hash import hash_float, hash_float2, hash_float3, hash_float4
from .noise import fbm

_MASK = 0xFFFFFFFF


@kernel
def _nudge(x):
    return (x + 0.000001) * 0.999999


@kernel
def checker(p):
    """1 on the cells of colour 1, 0 on those of colour 2."""
    xi = abs(int(math.floor(_nudge(p[0]))))
    yi = abs(int(math.floor(_nudge(p[1]))))
    zi = abs(int(math.floor(_nudge(p[2]))))
    return 1.0 if (xi % 2 == yi % 2) == (zi % 2 == 1) else 0.0


@kernel
def gradient(kind, p):
    """``GRADIENT_TYPES[kind]`` at ``p``, clamped to 0-1."""
    x, y, z = p
    if kind == 0:
        f = x
    elif kind == 1:
        r = max(x, 0.0)
        f = r * r
    elif kind == 2:
        r = min(max(x, 0.0), 1.0)
        t = r * r
        f = 3.0 * t - 2.0 * t * r
    elif kind == 3:
        f = (x + y) * 0.5
    elif kind == 6:
        f = math.atan2(y, x) / (2.0 * math.pi) + 0.5
    else:
        r = max(0.999999 - math.sqrt(x * x + y * y + z * z), 0.0)
        f = r * r if kind == 5 else r
    return min(max(f, 0.0), 1.0)


@kernel
def wave(kind, direction, profile, p, distortion, detail, detail_scale, detail_roughness, phase):
    """Blender's Wave Texture (``WAVE_TYPES[kind]``; ``direction`` indexes the bands or rings directions;
    ``WAVE_PROFILES[profile]``) at the scaled point ``p``."""
    p = (_nudge(p[0]), _nudge(p[1]), _nudge(p[2]))
    if kind == 0:
        if direction == 0:
            n = p[0] * 20.0
        elif direction == 1:
            n = p[1] * 20.0
        elif direction == 2:
            n = p[2] * 20.0
        else:
            n = (p[0] + p[1] + p[2]) * 10.0
    else:
        rx = 0.0 if direction == 0 else p[0]
        ry = 0.0 if direction == 1 else p[1]
        rz = 0.0 if direction == 2 else p[2]
        n = math.sqrt(rx * rx + ry * ry + rz * rz) * 20.0
    n += phase
    if distortion != 0.0:
        q = (p[0] * detail_scale, p[1] * detail_scale, p[2] * detail_scale, 0.0)
        n += distortion * (fbm(3, q, detail, detail_roughness, 2.0, True) * 2.0 - 1.0)
    if profile == 0:
        return 0.5 + 0.5 * math.sin(n - 0.5 * math.pi)
    n /= 2.0 * math.pi
    if profile == 1:
        return n - math.floor(n)
    return abs(n - math.floor(n + 0.5)) * 2.0


@kernel
def _brick_noise(n):
    n = (n + 1013) & 0x7FFFFFFF
    n = ((n >> 13) ^ n) & _MASK
    nn = (n * n) & _MASK
    nn = (nn * 60493 + 19990303) & _MASK
    nn = (n * nn + 1376312589) & 0x7FFFFFFF
    return 0.5 * (nn / 1073741824.0)


@kernel
def brick(p, mortar_size, mortar_smooth, bias, brick_width, row_height, offset_amount, offset_frequency,
          squash_amount, squash_frequency):
    """(tint, mortar) of Blender's Brick Texture at the scaled point ``p``."""
    row = int(math.floor(p[1] / row_height))
    offset = 0.0
    if offset_frequency != 0 and squash_frequency != 0:
        if row % squash_frequency == 0:
            brick_width *= squash_amount
        if row % offset_frequency == 0:
            offset = brick_width * offset_amount
    number = int(math.floor((p[0] + offset) / brick_width))
    x = (p[0] + offset) - brick_width * number
    y = p[1] - row_height * row
    tint = min(max(_brick_noise(((row << 16) + (number & 0xFFFF)) & _MASK) + bias, 0.0), 1.0)
    edge = min(min(x, y), min(brick_width - x, row_height - y))
    if edge >= mortar_size:
        mortar = 0.0
    elif mortar_smooth == 0.0:
        mortar = 1.0
    else:
        f = (1.0 - edge / mortar_size) / mortar_smooth
        if f <= 0.0:
            mortar = 0.0
        elif f >= 1.0:
            mortar = 1.0
        else:
            mortar = 3.0 * f * f - 2.0 * f * f * f
    return tint, mortar


@kernel
def magic(p, scale, depth, distortion):
    """Colour of Blender's Magic Texture (nested sines and cosines, ``depth`` levels)."""
    two_pi = 2.0 * math.pi
    px, py, pz = np.fmod(p[0], two_pi), np.fmod(p[1], two_pi), np.fmod(p[2], two_pi)
    x = math.sin((px + py + pz) * 5.0 * scale)
    y = math.cos((-px + py - pz) * 5.0 * scale)
    z = -math.cos((-px - py + pz) * 5.0 * scale)
    if depth > 0:
        x *= distortion
        y *= distortion
        z *= distortion
        y = -math.cos(x - y + z) * distortion
    if depth > 1:
        x = math.cos(x - y - z) * distortion
    if depth > 2:
        z = math.sin(-x - y - z) * distortion
    if depth > 3:
        x = -math.cos(-x + y - z) * distortion
    if depth > 4:
        y = -math.sin(-x + y + z) * distortion
    if depth > 5:
        y = -math.cos(-x + y + z) * distortion
    if depth > 6:
        x = math.cos(x + y + z) * distortion
    if depth > 7:
        z = math.sin(x + y - z) * distortion
    if depth > 8:
        x = -math.cos(-x - y + z) * distortion
    if depth > 9:
        y = -math.sin(x - y + z) * distortion
    if distortion != 0.0:
        d = 2.0 * distortion
        x /= d
        y /= d
        z /= d
    return (0.5 - x, 0.5 - y, 0.5 - z)


@kernel
def white_noise(dims, p, w):
    """(value, r, g, b) of Blender's White Noise Texture in ``dims`` dimensions (1-D reads ``w``)."""
    x, y, z = p
    if dims == 1:
        v = hash_float(w)
        return v, v, hash_float2(w, 1.0), hash_float2(w, 2.0)
    if dims == 2:
        v = hash_float2(x, y)
        return v, v, hash_float3(x, y, 1.0), hash_float3(x, y, 2.0)
    if dims == 3:
        v = hash_float3(x, y, z)
        return v, v, hash_float4(x, y, z, 1.0), hash_float4(x, y, z, 2.0)
    v = hash_float4(x, y, z, w)
    return v, v, hash_float4(z, x, w, y), hash_float4(w, z, y, x)
