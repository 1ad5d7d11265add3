"""Blender's Voronoi Texture in 2 and 3 dimensions: F1, F2, Smooth F1, Distance to Edge and N-Sphere
Radius, Euclidean/Manhattan/Chebychev/Minkowski distances, with Blender's fractal layering (Detail,
Roughness, Lacunarity) and normalisation.

One feature point per unit cell, jittered by Randomness with lookup3 hashes of the cell (``textures.hash``)
as Blender places them, so cells, colours and positions match Blender's. Points are 3-tuples (z unused in
2-D). Features and metrics are indices into ``materials.opcodes.VORONOI_FEATURES`` / ``VORONOI_METRICS``.
"""

from __future__ import annotations

import math

from ..jit import kernel
from .hash import hash_float2, hash_float3, hash_float4

F1, F2, SMOOTH_F1, DISTANCE_TO_EDGE, N_SPHERE_RADIUS = range(5)
_BIG = 3.4028234663852886e38


@kernel
def _cell_point(dims, c):
    """Jitter (0-1 per axis) of the feature point of cell ``c``."""
    if dims == 2:
        return (hash_float2(c[0], c[1]), hash_float3(c[0], c[1], 1.0), 0.0)
    return (hash_float3(c[0], c[1], c[2]), hash_float4(c[0], c[1], c[2], 1.0), hash_float4(c[0], c[1], c[2], 2.0))


@kernel
def _cell_colour(dims, c):
    if dims == 2:
        return (hash_float2(c[0], c[1]), hash_float3(c[0], c[1], 1.0), hash_float3(c[0], c[1], 2.0))
    return _cell_point(3, c)


@kernel
def _distance(metric, exponent, d, bound):
    """Distance of difference ``d`` (or a monotonic bound of it for comparisons, when ``bound``)."""
    ax, ay, az = abs(d[0]), abs(d[1]), abs(d[2])
    if metric == 0:
        s = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
        return s if bound else math.sqrt(s)
    if metric == 1:
        return ax + ay + az
    if metric == 2:
        return max(ax, ay, az)
    s = ax**exponent + ay**exponent + az**exponent
    return s if bound else s ** (1.0 / exponent)


@kernel
def _offsets(dims, reach):
    """Range of cell offsets along z (0 only in 2-D) for a search of ``reach`` cells around."""
    return (0, 0) if dims == 2 else (-reach, reach)


@kernel
def _smoothstep(x):
    x = min(max(x, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


@kernel
def _octave(dims, feature, metric, exponent, randomness, smoothness, coord):
    """(distance, colour, position) of one octave at ``coord`` (scaled)."""
    cell = (math.floor(coord[0]), math.floor(coord[1]), math.floor(coord[2]) if dims == 3 else 0.0)
    local = (coord[0] - cell[0], coord[1] - cell[1], coord[2] - cell[2] if dims == 3 else 0.0)
    zlo, zhi = _offsets(dims, 2 if feature == SMOOTH_F1 else 1)
    if feature == SMOOTH_F1:
        smooth_d = 0.0
        sc = (0.0, 0.0, 0.0)
        sp = (0.0, 0.0, 0.0)
        h = -1.0
        for k in range(zlo, zhi + 1):
            for j in range(-2, 3):
                for i in range(-2, 3):
                    c = (cell[0] + i, cell[1] + j, cell[2] + k)
                    jit = _cell_point(dims, c)
                    pt = (i + jit[0] * randomness, j + jit[1] * randomness, k + jit[2] * randomness)
                    d = _distance(metric, exponent, (pt[0] - local[0], pt[1] - local[1], pt[2] - local[2]), False)
                    h = 1.0 if h == -1.0 else _smoothstep(0.5 + 0.5 * (smooth_d - d) / smoothness)
                    correction = smoothness * h * (1.0 - h)
                    smooth_d = smooth_d + h * (d - smooth_d) - correction
                    correction /= 1.0 + 3.0 * smoothness
                    col = _cell_colour(dims, c)
                    sc = (sc[0] + h * (col[0] - sc[0]) - correction, sc[1] + h * (col[1] - sc[1]) - correction,
                          sc[2] + h * (col[2] - sc[2]) - correction)
                    sp = (sp[0] + h * (pt[0] - sp[0]) - correction, sp[1] + h * (pt[1] - sp[1]) - correction,
                          sp[2] + h * (pt[2] - sp[2]) - correction)
        return smooth_d, sc, (cell[0] + sp[0], cell[1] + sp[1], cell[2] + sp[2] if dims == 3 else 0.0)
    d1 = _BIG
    d2 = _BIG
    o1 = (0.0, 0.0, 0.0)
    o2 = (0.0, 0.0, 0.0)
    p1 = (0.0, 0.0, 0.0)
    p2 = (0.0, 0.0, 0.0)
    for k in range(zlo, zhi + 1):
        for j in range(-1, 2):
            for i in range(-1, 2):
                off = (float(i), float(j), float(k))
                jit = _cell_point(dims, (cell[0] + i, cell[1] + j, cell[2] + k))
                pt = (i + jit[0] * randomness, j + jit[1] * randomness, k + jit[2] * randomness)
                d = _distance(metric, exponent, (pt[0] - local[0], pt[1] - local[1], pt[2] - local[2]),
                              feature == F1)
                if d < d1:
                    d2, o2, p2 = d1, o1, p1
                    d1, o1, p1 = d, off, pt
                elif d < d2:
                    d2, o2, p2 = d, off, pt
    if feature == F2:
        d, o, p = d2, o2, p2
    else:
        d, o, p = _distance(metric, exponent, (p1[0] - local[0], p1[1] - local[1], p1[2] - local[2]), False), o1, p1
    colour = _cell_colour(dims, (cell[0] + o[0], cell[1] + o[1], cell[2] + o[2]))
    return d, colour, (cell[0] + p[0], cell[1] + p[1], cell[2] + p[2] if dims == 3 else 0.0)


@kernel
def _edge_distance(dims, randomness, coord):
    cell = (math.floor(coord[0]), math.floor(coord[1]), math.floor(coord[2]) if dims == 3 else 0.0)
    local = (coord[0] - cell[0], coord[1] - cell[1], coord[2] - cell[2] if dims == 3 else 0.0)
    zlo, zhi = _offsets(dims, 1)
    closest = (0.0, 0.0, 0.0)
    best = _BIG
    for k in range(zlo, zhi + 1):
        for j in range(-1, 2):
            for i in range(-1, 2):
                jit = _cell_point(dims, (cell[0] + i, cell[1] + j, cell[2] + k))
                v = (i + jit[0] * randomness - local[0], j + jit[1] * randomness - local[1],
                     k + jit[2] * randomness - local[2])
                d = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
                if d < best:
                    best = d
                    closest = v
    best = _BIG
    for k in range(zlo, zhi + 1):
        for j in range(-1, 2):
            for i in range(-1, 2):
                jit = _cell_point(dims, (cell[0] + i, cell[1] + j, cell[2] + k))
                v = (i + jit[0] * randomness - local[0], j + jit[1] * randomness - local[1],
                     k + jit[2] * randomness - local[2])
                q = (v[0] - closest[0], v[1] - closest[1], v[2] - closest[2])
                q2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2]
                if q2 > 0.0001:
                    n = math.sqrt(q2)
                    best = min(best, ((closest[0] + v[0]) * q[0] + (closest[1] + v[1]) * q[1]
                                      + (closest[2] + v[2]) * q[2]) / (2.0 * n))
    return best


@kernel
def _sphere_radius(dims, randomness, coord):
    cell = (math.floor(coord[0]), math.floor(coord[1]), math.floor(coord[2]) if dims == 3 else 0.0)
    local = (coord[0] - cell[0], coord[1] - cell[1], coord[2] - cell[2] if dims == 3 else 0.0)
    zlo, zhi = _offsets(dims, 1)
    closest = (0.0, 0.0, 0.0)
    closest_off = (0.0, 0.0, 0.0)
    best = _BIG
    for k in range(zlo, zhi + 1):
        for j in range(-1, 2):
            for i in range(-1, 2):
                jit = _cell_point(dims, (cell[0] + i, cell[1] + j, cell[2] + k))
                pt = (i + jit[0] * randomness, j + jit[1] * randomness, k + jit[2] * randomness)
                d = (pt[0] - local[0]) ** 2 + (pt[1] - local[1]) ** 2 + (pt[2] - local[2]) ** 2
                if d < best:
                    best = d
                    closest = pt
                    closest_off = (float(i), float(j), float(k))
    best = _BIG
    other = (0.0, 0.0, 0.0)
    for k in range(zlo, zhi + 1):
        for j in range(-1, 2):
            for i in range(-1, 2):
                if i == 0 and j == 0 and k == 0:
                    continue
                off = (i + closest_off[0], j + closest_off[1], k + closest_off[2])
                jit = _cell_point(dims, (cell[0] + off[0], cell[1] + off[1], cell[2] + off[2]))
                pt = (off[0] + jit[0] * randomness, off[1] + jit[1] * randomness, off[2] + jit[2] * randomness)
                d = (closest[0] - pt[0]) ** 2 + (closest[1] - pt[1]) ** 2 + (closest[2] - pt[2]) ** 2
                if d < best:
                    best = d
                    other = pt
    return 0.5 * math.sqrt((other[0] - closest[0]) ** 2 + (other[1] - closest[1]) ** 2
                           + (other[2] - closest[2]) ** 2)


@kernel
def voronoi_texture(dims, feature, metric, coord, scale, detail, roughness, lacunarity, smoothness, exponent,
                    randomness, normalize):
    """Blender's Voronoi Texture at ``coord`` (unscaled): (distance, colour, position, radius)."""
    detail = min(max(detail, 0.0), 15.0)
    roughness = min(max(roughness, 0.0), 1.0)
    randomness = min(max(randomness, 0.0), 1.0)
    smoothness = min(max(smoothness / 2.0, 0.0), 0.5)
    coord = (coord[0] * scale, coord[1] * scale, coord[2] * scale if dims == 3 else 0.0)
    zero = (0.0, 0.0, 0.0)
    if feature == N_SPHERE_RADIUS:
        return 0.0, zero, zero, _sphere_radius(dims, randomness, coord)
    half = 0.5 + 0.5 * randomness
    zero_input = detail == 0.0 or roughness == 0.0
    amplitude = 1.0
    octave_scale = 1.0
    if feature == DISTANCE_TO_EDGE:
        max_amplitude = half
        distance = 8.0
        for i in range(int(math.ceil(detail)) + 1):
            d = _edge_distance(dims, randomness, (coord[0] * octave_scale, coord[1] * octave_scale,
                                                  coord[2] * octave_scale))
            if zero_input:
                distance = d
                break
            if i <= detail:
                max_amplitude += amplitude * (half / octave_scale - max_amplitude)
                distance += amplitude * (min(distance, d / octave_scale) - distance)
                octave_scale *= lacunarity
                amplitude *= roughness
            else:
                rmd = detail - math.floor(detail)
                if rmd != 0.0:
                    lerp_amplitude = max_amplitude + amplitude * (half / octave_scale - max_amplitude)
                    max_amplitude += rmd * (lerp_amplitude - max_amplitude)
                    lerp_distance = distance + amplitude * (min(distance, d / octave_scale) - distance)
                    distance += rmd * (min(distance, lerp_distance) - distance)
        if normalize:
            distance /= max_amplitude
        return distance, zero, zero, 0.0
    if smoothness == 0.0 and feature == SMOOTH_F1:
        feature = F1
    max_distance = _distance(metric, exponent, (half, half, half if dims == 3 else 0.0), False)
    if feature == F2:
        max_distance *= 2.0
    max_amplitude = 0.0
    distance = 0.0
    colour = zero
    position = zero
    for i in range(int(math.ceil(detail)) + 1):
        d, c, p = _octave(dims, feature, metric, exponent, randomness, smoothness,
                          (coord[0] * octave_scale, coord[1] * octave_scale, coord[2] * octave_scale))
        if zero_input:
            max_amplitude = 1.0
            distance, colour, position = d, c, p
            break
        p = (p[0] / octave_scale, p[1] / octave_scale, p[2] / octave_scale)
        if i <= detail:
            max_amplitude += amplitude
            distance += d * amplitude
            colour = (colour[0] + c[0] * amplitude, colour[1] + c[1] * amplitude, colour[2] + c[2] * amplitude)
            position = (position[0] + amplitude * (p[0] - position[0]), position[1] + amplitude * (p[1] - position[1]),
                        position[2] + amplitude * (p[2] - position[2]))
            octave_scale *= lacunarity
            amplitude *= roughness
        else:
            rmd = detail - math.floor(detail)
            if rmd != 0.0:
                max_amplitude += rmd * amplitude
                distance += rmd * d * amplitude
                colour = (colour[0] + rmd * c[0] * amplitude, colour[1] + rmd * c[1] * amplitude,
                          colour[2] + rmd * c[2] * amplitude)
                position = (position[0] + rmd * amplitude * (p[0] - position[0]),
                            position[1] + rmd * amplitude * (p[1] - position[1]),
                            position[2] + rmd * amplitude * (p[2] - position[2]))
    if normalize:
        distance /= max_amplitude * max_distance
        colour = (colour[0] / max_amplitude, colour[1] / max_amplitude, colour[2] / max_amplitude)
    if scale != 0.0:
        position = (position[0] / scale, position[1] / scale, position[2] / scale)
    else:
        position = zero
    return distance, colour, position, 0.0
