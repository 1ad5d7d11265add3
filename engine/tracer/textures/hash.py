"""Integer hashes for procedural textures: Bob Jenkins' lookup3 final mix, as Blender seeds its noise,
Voronoi and white-noise textures with (so the same coordinates give the same pattern).

Values are unsigned 32-bit integers held in int64 and masked after every step; a float is hashed by its
float32 bit pattern (``float_bits``), as Blender does.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel

_MASK = 0xFFFFFFFF
_SEED = 0xDEADBEEF


@kernel
def _rot(x, k):
    return ((x << k) | (x >> (32 - k))) & _MASK


@kernel
def _final(a, b, c):
    c = ((c ^ b) - _rot(b, 14)) & _MASK
    a = ((a ^ c) - _rot(c, 11)) & _MASK
    b = ((b ^ a) - _rot(a, 25)) & _MASK
    c = ((c ^ b) - _rot(b, 16)) & _MASK
    a = ((a ^ c) - _rot(c, 4)) & _MASK
    b = ((b ^ a) - _rot(a, 14)) & _MASK
    c = ((c ^ b) - _rot(b, 24)) & _MASK
    return c


@kernel
def _mix(a, b, c):
    a = (a - c) & _MASK
    a ^= _rot(c, 4)
    c = (c + b) & _MASK
    b = (b - a) & _MASK
    b ^= _rot(a, 6)
    a = (a + c) & _MASK
    c = (c - b) & _MASK
    c ^= _rot(b, 8)
    b = (b + a) & _MASK
    a = (a - c) & _MASK
    a ^= _rot(c, 16)
    c = (c + b) & _MASK
    b = (b - a) & _MASK
    b ^= _rot(a, 19)
    a = (a + c) & _MASK
    c = (c - b) & _MASK
    c ^= _rot(b, 4)
    b = (b + a) & _MASK
    return a, b, c


@kernel
def hash1(kx):
    a = (_SEED + (1 << 2) + 13 + (kx & _MASK)) & _MASK
    b = (_SEED + (1 << 2) + 13) & _MASK
    return _final(a, b, b)


@kernel
def hash2(kx, ky):
    init = (_SEED + (2 << 2) + 13) & _MASK
    return _final((init + (kx & _MASK)) & _MASK, (init + (ky & _MASK)) & _MASK, init)


@kernel
def hash3(kx, ky, kz):
    init = (_SEED + (3 << 2) + 13) & _MASK
    return _final((init + (kx & _MASK)) & _MASK, (init + (ky & _MASK)) & _MASK, (init + (kz & _MASK)) & _MASK)


@kernel
def hash4(kx, ky, kz, kw):
    init = (_SEED + (4 << 2) + 13) & _MASK
    a, b, c = _mix((init + (kx & _MASK)) & _MASK, (init + (ky & _MASK)) & _MASK, (init + (kz & _MASK)) & _MASK)
    return _final((a + (kw & _MASK)) & _MASK, b, c)


@kernel
def to_unit(h):
    """A hash as a float in [0, 1]."""
    return h * (1.0 / 4294967295.0)


@kernel
def float_bits(x):
    """The float32 bit pattern of ``x`` rounded to float32 (as Blender hashes floats)."""
    v = float(np.float32(x))
    if v == 0.0:
        return 0x80000000 if math.copysign(1.0, v) < 0.0 else 0
    sign = 0x80000000 if v < 0.0 else 0
    a = abs(v)
    if not math.isfinite(a):
        return sign | (0x7F800000 if a == math.inf else 0x7FC00000)
    m, e = math.frexp(a)
    exponent = e + 126
    if exponent <= 0:
        return sign | int(a * 2.0**149)
    return sign | (exponent << 23) | int((2.0 * m - 1.0) * 8388608.0)


@kernel
def hash_float(x):
    return to_unit(hash1(float_bits(x)))


@kernel
def hash_float2(x, y):
    return to_unit(hash2(float_bits(x), float_bits(y)))


@kernel
def hash_float3(x, y, z):
    return to_unit(hash3(float_bits(x), float_bits(y), float_bits(z)))


@kernel
def hash_float4(x, y, z, w):
    return to_unit(hash4(float_bits(x), float_bits(y), float_bits(z), float_bits(w)))
