"""Blender's Noise Texture: Perlin noise in 1-4 dimensions with its fractal variants (fBM,
multifractal, hybrid multifractal, ridged multifractal, hetero terrain), distortion and colour output.

Gradient noise (Perlin's improved noise: quintic fade, 16/32 gradient directions picked by lookup3
hashes of the lattice corners, ``textures.hash``), scaled per dimension as Blender scales it
(0.25, 0.6616, 0.982, 0.8344) so the signed noise stays within about [-1, 1]; coordinates repeat every
100000 units (as Blender, against float precision). A point is a 4-tuple (x, y, z, w); ``dims`` says how
many components are used. Types are indices into ``materials.opcodes.NOISE_TYPES``.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel
from .hash import hash1, hash2, hash3, hash4, hash_float, hash_float2

_SCALE = (0.0, 0.25, 0.6616, 0.982, 0.8344)


@kernel
def _fade(t):
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


@kernel
def _negate_if(value, condition):
    return -value if condition else value


@kernel
def _grad1(h, x):
    h = h & 15
    g = 1.0 + (h & 7)
    return _negate_if(g, h & 8) * x


@kernel
def _grad2(h, x, y):
    h = h & 7
    u = x if h < 4 else y
    v = 2.0 * (y if h < 4 else x)
    return _negate_if(u, h & 1) + _negate_if(v, h & 2)


@kernel
def _grad3(h, x, y, z):
    h = h & 15
    u = x if h < 8 else y
    vt = x if (h == 12 or h == 14) else z
    v = y if h < 4 else vt
    return _negate_if(u, h & 1) + _negate_if(v, h & 2)


@kernel
def _grad4(h, x, y, z, w):
    h = h & 31
    u = x if h < 24 else y
    v = y if h < 16 else z
    s = z if h < 8 else w
    return _negate_if(u, h & 1) + _negate_if(v, h & 2) + _negate_if(s, h & 4)


@kernel
def _lerp(a, b, t):
    return (1.0 - t) * a + t * b


@kernel
def _perlin1(x):
    fx = math.floor(x)
    i = int(fx)
    f = x - fx
    return _lerp(_grad1(hash1(i), f), _grad1(hash1(i + 1), f - 1.0), _fade(f))


@kernel
def _perlin2(x, y):
    fx, fy = math.floor(x), math.floor(y)
    i, j = int(fx), int(fy)
    x, y = x - fx, y - fy
    u, v = _fade(x), _fade(y)
    a = _lerp(_grad2(hash2(i, j), x, y), _grad2(hash2(i + 1, j), x - 1.0, y), u)
    b = _lerp(_grad2(hash2(i, j + 1), x, y - 1.0), _grad2(hash2(i + 1, j + 1), x - 1.0, y - 1.0), u)
    return _lerp(a, b, v)


@kernel
def _perlin3_layer(i, j, k, x, y, z, u, v):
    a = _lerp(_grad3(hash3(i, j, k), x, y, z), _grad3(hash3(i + 1, j, k), x - 1.0, y, z), u)
    b = _lerp(_grad3(hash3(i, j + 1, k), x, y - 1.0, z), _grad3(hash3(i + 1, j + 1, k), x - 1.0, y - 1.0, z), u)
    return _lerp(a, b, v)


@kernel
def _perlin3(x, y, z):
    fx, fy, fz = math.floor(x), math.floor(y), math.floor(z)
    i, j, k = int(fx), int(fy), int(fz)
    x, y, z = x - fx, y - fy, z - fz
    u, v, w = _fade(x), _fade(y), _fade(z)
    return _lerp(_perlin3_layer(i, j, k, x, y, z, u, v), _perlin3_layer(i, j, k + 1, x, y, z - 1.0, u, v), w)


@kernel
def _perlin4_layer(i, j, k, m, x, y, z, w, u, v):
    a = _lerp(_grad4(hash4(i, j, k, m), x, y, z, w), _grad4(hash4(i + 1, j, k, m), x - 1.0, y, z, w), u)
    b = _lerp(_grad4(hash4(i, j + 1, k, m), x, y - 1.0, z, w),
              _grad4(hash4(i + 1, j + 1, k, m), x - 1.0, y - 1.0, z, w), u)
    return _lerp(a, b, v)


@kernel
def _perlin4(x, y, z, w):
    fx, fy, fz, fw = math.floor(x), math.floor(y), math.floor(z), math.floor(w)
    i, j, k, m = int(fx), int(fy), int(fz), int(fw)
    x, y, z, w = x - fx, y - fy, z - fz, w - fw
    u, v, t, s = _fade(x), _fade(y), _fade(z), _fade(w)
    low = _lerp(_perlin4_layer(i, j, k, m, x, y, z, w, u, v),
                _perlin4_layer(i, j, k + 1, m, x, y, z - 1.0, w, u, v), t)
    high = _lerp(_perlin4_layer(i, j, k, m + 1, x, y, z, w - 1.0, u, v),
                 _perlin4_layer(i, j, k + 1, m + 1, x, y, z - 1.0, w - 1.0, u, v), t)
    return _lerp(low, high, s)


@kernel
def _wrap(x):
    return np.fmod(x, 100000.0) + (0.5 if abs(x) >= 1000000.0 else 0.0)


@kernel
def snoise(dims, p):
    """Signed Perlin noise (about -1..1) of the first ``dims`` components of 4-tuple ``p``."""
    x, y, z, w = _wrap(p[0]), _wrap(p[1]), _wrap(p[2]), _wrap(p[3])
    if dims == 1:
        return _SCALE[1] * _perlin1(x)
    if dims == 2:
        return _SCALE[2] * _perlin2(x, y)
    if dims == 3:
        return _SCALE[3] * _perlin3(x, y, z)
    return _SCALE[4] * _perlin4(x, y, z, w)


@kernel
def _scaled(p, s):
    return (p[0] * s, p[1] * s, p[2] * s, p[3] * s)


@kernel
def fbm(dims, p, detail, roughness, lacunarity, normalize):
    scale = 1.0
    amp = 1.0
    maxamp = 0.0
    total = 0.0
    for _ in range(int(detail) + 1):
        total += snoise(dims, _scaled(p, scale)) * amp
        maxamp += amp
        amp *= roughness
        scale *= lacunarity
    rmd = detail - math.floor(detail)
    if rmd != 0.0:
        total2 = total + snoise(dims, _scaled(p, scale)) * amp
        if normalize:
            return _lerp(0.5 * total / maxamp + 0.5, 0.5 * total2 / (maxamp + amp) + 0.5, rmd)
        return _lerp(total, total2, rmd)
    return 0.5 * total / maxamp + 0.5 if normalize else total


@kernel
def multifractal(dims, p, detail, roughness, lacunarity):
    value = 1.0
    pwr = 1.0
    for _ in range(int(detail) + 1):
        value *= pwr * snoise(dims, p) + 1.0
        pwr *= roughness
        p = _scaled(p, lacunarity)
    rmd = detail - math.floor(detail)
    if rmd != 0.0:
        value *= rmd * pwr * snoise(dims, p) + 1.0
    return value


@kernel
def hetero_terrain(dims, p, detail, roughness, lacunarity, offset):
    pwr = roughness
    value = offset + snoise(dims, p)
    p = _scaled(p, lacunarity)
    for _ in range(1, int(detail) + 1):
        value += (snoise(dims, p) + offset) * pwr * value
        pwr *= roughness
        p = _scaled(p, lacunarity)
    rmd = detail - math.floor(detail)
    if rmd != 0.0:
        value += rmd * (snoise(dims, p) + offset) * pwr * value
    return value


@kernel
def hybrid_multifractal(dims, p, detail, roughness, lacunarity, offset, gain):
    pwr = 1.0
    value = 0.0
    weight = 1.0
    i = 0
    while weight > 0.001 and i <= int(detail):
        weight = min(weight, 1.0)
        signal = (snoise(dims, p) + offset) * pwr
        pwr *= roughness
        value += weight * signal
        weight *= gain * signal
        p = _scaled(p, lacunarity)
        i += 1
    rmd = detail - math.floor(detail)
    if rmd != 0.0 and weight > 0.001:
        weight = min(weight, 1.0)
        value += rmd * weight * (snoise(dims, p) + offset) * pwr
    return value


@kernel
def ridged_multifractal(dims, p, detail, roughness, lacunarity, offset, gain):
    pwr = roughness
    signal = offset - abs(snoise(dims, p))
    signal *= signal
    value = signal
    for _ in range(1, int(detail) + 1):
        p = _scaled(p, lacunarity)
        weight = min(max(signal * gain, 0.0), 1.0)
        signal = offset - abs(snoise(dims, p))
        signal = signal * signal * weight
        value += signal * pwr
        pwr *= roughness
    return value


@kernel
def fractal(kind, dims, p, detail, roughness, lacunarity, offset, gain, normalize):
    """The fractal of ``NOISE_TYPES[kind]``."""
    if kind == 0:
        return multifractal(dims, p, detail, roughness, lacunarity)
    if kind == 1:
        return ridged_multifractal(dims, p, detail, roughness, lacunarity, offset, gain)
    if kind == 2:
        return hybrid_multifractal(dims, p, detail, roughness, lacunarity, offset, gain)
    if kind == 4:
        return hetero_terrain(dims, p, detail, roughness, lacunarity, offset)
    return fbm(dims, p, detail, roughness, lacunarity, normalize)


@kernel
def random_offset(dims, seed):
    """Blender's per-seed offset (100-200) of noise coordinates, component by component."""
    if dims == 1:
        return (100.0 + hash_float(seed) * 100.0, 0.0, 0.0, 0.0)
    return (100.0 + hash_float2(seed, 0.0) * 100.0, 100.0 + hash_float2(seed, 1.0) * 100.0,
            100.0 + hash_float2(seed, 2.0) * 100.0 if dims > 2 else 0.0,
            100.0 + hash_float2(seed, 3.0) * 100.0 if dims > 3 else 0.0)


@kernel
def _plus(p, q):
    return (p[0] + q[0], p[1] + q[1], p[2] + q[2], p[3] + q[3])


@kernel
def noise_texture(kind, dims, p, detail, roughness, lacunarity, offset, gain, distortion, normalize, colour):
    """Blender's Noise Texture at the (already scaled) point ``p``: (fac, r, g, b); g and b are 0 unless
    ``colour`` is needed."""
    detail = min(max(detail, 0.0), 15.0)
    roughness = max(roughness, 0.0)
    if distortion != 0.0:
        d0 = snoise(dims, _plus(p, random_offset(dims, 0.0))) * distortion
        d1 = snoise(dims, _plus(p, random_offset(dims, 1.0))) * distortion if dims > 1 else 0.0
        d2 = snoise(dims, _plus(p, random_offset(dims, 2.0))) * distortion if dims > 2 else 0.0
        d3 = snoise(dims, _plus(p, random_offset(dims, 3.0))) * distortion if dims > 3 else 0.0
        p = (p[0] + d0, p[1] + d1, p[2] + d2, p[3] + d3)
    value = fractal(kind, dims, p, detail, roughness, lacunarity, offset, gain, normalize)
    if not colour:
        return value, value, 0.0, 0.0
    first = 1.0 if dims == 1 else float(dims)
    g = fractal(kind, dims, _plus(p, random_offset(dims, first)), detail, roughness, lacunarity, offset, gain,
                normalize)
    b = fractal(kind, dims, _plus(p, random_offset(dims, first + 1.0)), detail, roughness, lacunarity, offset,
                gain, normalize)
    return value, value, g, b
