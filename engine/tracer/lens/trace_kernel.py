"""Tracing one ray through a lens system, compiled: the only lens tracer.

Works on ``LensTables`` (lens coordinates, mm, float64). A ray meets the surfaces in order
(front to rear toward the film, rear to front toward the scene); at each one it dies if it
misses the surface's sphere, lands outside the clear aperture (or the stop's opening), or is
totally internally reflected; otherwise it refracts by Snell's law with the indices of the
media on both sides at its wavelength (the stop never refracts). ``trace_rays`` loops
``trace_ray`` over a batch for ``LensSystem.trace``.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..spectra.dispersion import refractive_index
from .ray_fate import FATE_ALIVE, FATE_BLOCKED, FATE_MISSED, FATE_TIR


@kernel
def intersect_surface(z_vertex_mm, curvature_per_mm, origin, direction):
    """Distance along unit ``direction`` from ``origin`` to the spherical cap through the vertex
    at ``z_vertex_mm`` (on the axis), or -1 if the ray does not meet it.

    The sphere is c|p|^2 - 2 p_z = 0 (p relative to the vertex), so a flat surface is the
    limit c = 0. Of the two roots (stable quadratic formula) the nearest in front of the ray
    on the vertex's hemisphere (1 - c p_z > 0) is taken.
    """
    c = curvature_per_mm
    x, y, z = origin[0], origin[1], origin[2] - z_vertex_mm
    dx, dy, dz = direction
    b = c * (x * dx + y * dy + z * dz) - dz
    cc = c * (x * x + y * y + z * z) - 2.0 * z
    disc = b * b - c * cc
    if disc < 0.0:
        return -1.0
    q = -(b + math.copysign(math.sqrt(disc), b))
    near = cc / q if q != 0.0 else math.inf
    far = q / c if c != 0.0 else math.inf
    t = math.inf
    if near > 0.0 and near < t and 1.0 - c * (z + near * dz) > 0.0:
        t = near
    if far > 0.0 and far < t and 1.0 - c * (z + far * dz) > 0.0:
        t = far
    return t if t < math.inf else -1.0


@kernel
def refract_at_surface(z_vertex_mm, curvature_per_mm, point, direction, eta):
    """(refracted direction, total internal reflection?) of unit ``direction`` at ``point`` on the surface.

    ``eta`` = n_incident / n_transmitted. The normal c (p - centre) is a unit vector for a
    point on the sphere (and (0, 0, -1) on a flat surface), so it needs no normalising; it is
    oriented against the ray, so the same formula serves both tracing directions. The
    result is unit up to rounding (``trace_ray`` normalises once at the end). Under TIR
    the direction is returned unchanged.
    """
    c = curvature_per_mm
    nx, ny, nz = c * point[0], c * point[1], c * (point[2] - z_vertex_mm) - 1.0
    dx, dy, dz = direction
    cos_i = -(nx * dx + ny * dy + nz * dz)
    sign = 1.0
    if cos_i < 0.0:
        sign, cos_i = -1.0, -cos_i
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    if k < 0.0:
        return direction, True
    g = (eta * cos_i - math.sqrt(k)) * sign
    return (eta * dx + g * nx, eta * dy + g * ny, eta * dz + g * nz), False


@kernel
def trace_ray(lens, origin, direction, wavelength_nm, toward_film, path_mm):
    """Trace one ray through every surface of ``lens`` (``LensTables``).

    ``origin`` (mm) and ``direction`` (need not be unit) are 3-tuples in lens coordinates;
    ``toward_film`` True traces from the scene in through the front element, False from
    the film out through the rear element. ``path_mm``: ``None``, or an [S + 1, 3] array that
    receives the start point and each intersection in the order the ray meets the surfaces
    (entries after the ray's death are left as they were; a ray blocked by an aperture
    records the point where it hit the blocking surface).

    Returns ``(fate, surface, origin, direction)``: a ``FATE_*`` code, the index of the
    surface where the ray died (-1 if alive), and where the ray leaves the last surface
    with its unit direction (the start point and unit start direction if it died).
    """
    count = lens.vertex_z_mm.shape[0]
    inv = 1.0 / math.sqrt(direction[0] ** 2 + direction[1] ** 2 + direction[2] ** 2)
    start_direction = (direction[0] * inv, direction[1] * inv, direction[2] * inv)
    if path_mm is not None:
        path_mm[0, 0], path_mm[0, 1], path_mm[0, 2] = origin
    p, d = origin, start_direction
    n_here = refractive_index(lens.medium_rows[0 if toward_film else count], wavelength_nm)[0]
    for step in range(count):
        i = step if toward_film else count - 1 - step
        z_vertex = lens.vertex_z_mm[i]
        c = lens.curvature_per_mm[i]
        t = intersect_surface(z_vertex, c, p, d)
        if t < 0.0:
            return FATE_MISSED, i, origin, start_direction
        p = (p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2])
        if path_mm is not None:
            path_mm[step + 1, 0], path_mm[step + 1, 1], path_mm[step + 1, 2] = p
        semi = lens.semi_aperture_mm[i]
        if p[0] * p[0] + p[1] * p[1] > semi * semi:
            return FATE_BLOCKED, i, origin, start_direction
        n_next = refractive_index(lens.medium_rows[i + 1 if toward_film else i], wavelength_nm)[0]
        if not lens.is_stop[i] and n_next != n_here:
            d, tir = refract_at_surface(z_vertex, c, p, d, n_here / n_next)
            if tir:
                return FATE_TIR, i, origin, start_direction
        n_here = n_next
    inv = 1.0 / math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    return FATE_ALIVE, -1, p, (d[0] * inv, d[1] * inv, d[2] * inv)


@kernel
def trace_rays(lens, origins, directions, wavelength_nm, toward_film, out_origins, out_directions, fate, surface,
               paths):
    """``trace_ray`` for each row of ``origins``/``directions`` [N, 3] at ``wavelength_nm`` [N],
    into ``out_origins``/``out_directions`` [N, 3], ``fate`` [N] int8, ``surface`` [N] int32 and,
    unless ``paths`` is ``None``, ``paths`` [N, S + 1, 3] (pre-filled with NaN)."""
    for k in range(origins.shape[0]):
        origin = (origins[k, 0], origins[k, 1], origins[k, 2])
        direction = (directions[k, 0], directions[k, 1], directions[k, 2])
        if paths is None:
            result = trace_ray(lens, origin, direction, wavelength_nm[k], toward_film, None)
        else:
            result = trace_ray(lens, origin, direction, wavelength_nm[k], toward_film, paths[k])
        fate[k], surface[k] = result[0], result[1]
        out_origins[k, 0], out_origins[k, 1], out_origins[k, 2] = result[2]
        out_directions[k, 0], out_directions[k, 1], out_directions[k, 2] = result[3]
