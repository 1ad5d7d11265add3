"""Light sampling and light hits, dispatched on each light's kind."""

from __future__ import annotations

import math

from ..jit import inlined
from ..materials.emitters import emission_at
from ..materials.light_path import sampled_distance
from ..materials.table import MAT_EMISSION_VARIES
from ..spectra.table import spectrum_value
from ..warps import cdf_index
from . import area, environment, mesh, point, sun
from .row import DISK, ENVIRONMENT, L_CAMERA, L_KIND, L_SPECTRUM, MESH, POINT, RECTANGLE, SPHERE, SUN, SUN_DISK


@inlined
def pick_light(lights, u):
    """(light index, u rescaled to [0, 1) within its interval) for a light chosen ∝ select_prob."""
    cdf = lights.select_cdf
    lo = cdf_index(cdf, u)
    below = cdf[lo - 1] if lo > 0 else 0.0
    prob = lights.select_prob[lo]
    return lo, min(max((u - below) / prob, 0.0), 0.9999999999999999) if prob > 0.0 else 0.0


@inlined
def sample_light(lights, materials, spectra, geometry, p, u_select, u1, u2, wavelength_nm, li, rows, regs, time):
    """Sample one light for the point ``p`` at ray time ``time``: (wi, distance (inf: distant), pdf including the
    light's selection probability, delta, light group or -1, emitter: the light's row, or rows + the render
    triangle sampled on an emissive mesh, for ``light_linking``); ``li[k]`` = incident radiance
    (irradiance for delta lights). ``rows`` and ``regs`` are scratch memory for emissive materials whose emission varies
    over the surface."""
    index, u_rest = pick_light(lights, u_select)
    row = lights.rows[index]
    kind = int(row[L_KIND])
    if kind == MESH:
        wi, dist, pdf, e, b1, b2 = mesh.sample_point(lights.mesh, geometry, p, u_rest, u1, u2, time)
        material = lights.mesh.material[e]
        if materials.flags[material] & MAT_EMISSION_VARIES:
            sampled_distance(regs, dist)  # the Light Path node's Ray Length, if the emitter reads it
            emission_at(materials, spectra, geometry, material, lights.mesh.triangle[e], b1, b2, time,
                        (-wi[0], -wi[1], -wi[2]), wavelength_nm, rows, regs, li, None)
        else:
            strength = materials.emission_strength[material]
            sid = materials.emission_spectrum[material]
            for k in range(li.shape[0]):
                li[k] = strength * spectrum_value(spectra, sid, wavelength_nm[k])
        return (wi, dist, pdf * lights.select_prob[index], False, lights.mesh.group[e],
                lights.rows.shape[0] + lights.mesh.triangle[e])
    if kind == ENVIRONMENT:
        wi, pdf = environment.sample_li(lights.environment, u1, u2)
        environment.radiance(lights.environment, spectra, wi, wavelength_nm, li)
        return wi, math.inf, pdf * lights.select_prob[index], False, lights.group[index], index
    if kind == POINT or kind == SPHERE:
        wi, dist, pdf, factor = point.sample_li(row, p, u1, u2)
    elif kind == RECTANGLE or kind == DISK:
        wi, dist, pdf, factor = area.sample_li(row, p, u1, u2)
    else:
        wi, dist, pdf, factor = sun.sample_li(row, p, u1, u2)
    sid = int(row[L_SPECTRUM])
    for k in range(li.shape[0]):
        li[k] = factor * spectrum_value(spectra, sid, wavelength_nm[k])
    return wi, dist, pdf * lights.select_prob[index], kind == POINT or kind == SUN, lights.group[index], index


@inlined
def light_distance(lights, index, o, d):
    """Distance along the ray to hittable light ``index`` (inf: missed)."""
    row = lights.rows[index]
    if int(row[L_KIND]) == SPHERE:
        return point.hit_distance(row, o, d)
    return area.intersect(row, o, d)


@inlined
def intersect_light(lights, o, d, t_max):
    """The closest hittable light along the ray before ``t_max``: (light index or -1, distance)."""
    best = -1
    t_best = t_max
    for h in range(lights.hittable.shape[0]):
        index = lights.hittable[h]
        t = light_distance(lights, index, o, d)
        if t < t_best:
            best = index
            t_best = t
    return best, t_best


@inlined
def light_hit(lights, index, o, d, t):
    """(radiance factor, light-sampling pdf incl. selection) of hittable light ``index`` seen along a
    ray from ``o`` at distance ``t``."""
    row = lights.rows[index]
    if int(row[L_KIND]) == SPHERE:
        return point.le(row, o, d, t), point.pdf_li(row, o, d, t) * lights.select_prob[index]
    return area.le(row, o, d, t), area.pdf_li(row, o, d, t) * lights.select_prob[index]


@inlined
def emitter_pdf(lights, geometry, triangle, d, t, time):
    """Light-sampling pdf (incl. selection) of an emissive triangle hit along ``d`` at distance ``t`` at ray time
    ``time`` (0 for a sphere: rows past the triangles are never light-sampled)."""
    if lights.mesh_index < 0 or triangle >= lights.mesh.of_triangle.shape[0]:
        return 0.0
    return mesh.pdf_li(lights.mesh, geometry, triangle, d, t, time) * lights.select_prob[lights.mesh_index]


@inlined
def light_spectrum(lights, index):
    return int(lights.rows[index, L_SPECTRUM])


@inlined
def is_distant(lights, index):
    return int(lights.rows[index, L_KIND]) == SUN_DISK


@inlined
def seen_by_camera(lights, index):
    return lights.rows[index, L_CAMERA] != 0.0


@inlined
def environment_pdf(lights, d):
    """Light-sampling density (incl. selection) of the background along an escaping ray ``d``; 0 when
    the background is not light-sampled."""
    index = lights.environment_index
    if index < 0:
        return 0.0
    return environment.pdf_li(lights.environment, d) * lights.select_prob[index]


@inlined
def distant_hit(lights, index, d):
    """(radiance factor, pdf incl. selection) of sun disc ``index`` along an escaping ray ``d``."""
    row = lights.rows[index]
    return sun.le_escaped(row, d), sun.pdf_escaped(row, d) * lights.select_prob[index]


@inlined
def emitter_group(lights, triangle):
    """Light group of an emissive triangle (-1: none, and for spheres)."""
    if triangle >= lights.mesh.of_triangle.shape[0]:
        return -1
    e = lights.mesh.of_triangle[triangle]
    return lights.mesh.group[e] if e >= 0 else -1
