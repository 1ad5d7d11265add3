"""Rays a material traces itself: Blender's Ambient Occlusion and Bevel nodes, as Cycles' ``svm_ao`` and
``svm_bevel`` define them.

Both run only where Cycles runs them: at a surface a path's ray hit (``stages.shade``), which passes a
``ShaderRays`` record. Light sampling's emitters, shadow rays crossing cut-outs and light paths evaluate
materials without one (``None``: numba compiles that variant without the rays), where Ambient Occlusion
reads 1 and Bevel the shading normal, as in Cycles' light and shadow shader evaluations.

- **Ambient Occlusion**: the fraction of ``samples`` cosine-weighted directions about the normal (flipped
  with Inside) that meet nothing within Distance (the World's Ambient Occlusion distance where the node's
  is 0 and unlinked: resolved by the compiler). Only Local counts only the hit's own object.
- **Bevel**: the normals of the hit object's surface within Radius, averaged with the weights of Cycles'
  disk sampling (Christensen-style cubic falloff, a probe ray along one of three axes, MIS between them:
  King et al. 2013, "BSSRDF importance sampling"); the shading normal where nothing is found, for a
  radius or sample count of 0, and after a blurry bounce (the path's least likely bounce pdf below 8, as
  Cycles skips it there).

Random numbers are the path's own Sobol dimensions (``sampler.shader_ray_slot``): N samples of a node
take indices ``sample × N .. sample × N + N - 1``, so a pixel's samples together are one stratified set.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..embree.queries import closest_hit, is_occluded
from ..geometry import FRAME_TIME, OFFSET_ABSOLUTE, OFFSET_RELATIVE, offset_origin, surface_at
from ..jit import inlined, kernel
from ..sampler import sample_2d, shader_ray_slot
from ..vec3 import tangents
from ..warps import cosine_hemisphere
from . import opcodes as op
from .hit_inputs import object_row

#: What a material's own rays need at a hit: ``caster`` (``embree.queries.RayCaster``), the path's sampler
#: ``kind``, pixel ``seed``, ``sample`` index and bounce ``depth``, its ray ``time`` and ``min_pdf`` (the
#: smallest pdf of its non-specular bounces: ``PathState.min_pdf``).
ShaderRays = namedtuple("ShaderRays", "caster kind seed sample depth time min_pdf")

AO_SLOT, BEVEL_SLOT = 0, 1
#: Hits of other objects a probe ray steps past before it gives up (bounds the time of a local query).
MAX_STEPS = 16
#: Cycles skips Bevel on paths whose least likely bounce had a pdf below this ("blurry indirect rays").
BEVEL_MIN_PDF = 8.0


@inlined
def step_past(origin, direction, t):
    """The point just past distance ``t`` along a ray, and how far that is (Embree's rays start at 0)."""
    q = (origin[0] + t * direction[0], origin[1] + t * direction[1], origin[2] + t * direction[2])
    eps = OFFSET_RELATIVE * max(abs(q[0]), abs(q[1]), abs(q[2])) + OFFSET_ABSOLUTE
    step = t + eps
    return (origin[0] + step * direction[0], origin[1] + step * direction[1], origin[2] + step * direction[2]), step


@inlined
def _hits_own_object(rays, attrs, origin, direction, tmax, row):
    """Whether the ray meets a surface of object ``row`` before ``tmax`` (others are stepped past)."""
    origin = (float(origin[0]), float(origin[1]), float(origin[2]))
    travelled = 0.0
    for _ in range(MAX_STEPS):
        hit, t, _u, _v = closest_hit(rays.caster, origin[0], origin[1], origin[2], direction[0], direction[1],
                                     direction[2], tmax - travelled, rays.time)
        if hit < 0:
            return False
        if object_row(attrs, hit) == row:
            return True
        origin, step = step_past(origin, direction, float(t))
        travelled += step
        if travelled >= tmax:
            return False
    return False


@inlined
def ambient_occlusion(rays, geometry, triangle, p, ng, normal, distance, mode):
    """The Ambient Occlusion node's AO at a hit: ``p`` camera-relative, ``ng`` the geometric normal facing
    the ray, ``normal`` the node's (unit; the shading normal unless linked), ``mode`` the instruction's."""
    samples = mode // op.AO_SAMPLES
    if distance <= 0.0 or samples < 1:
        return 1.0
    n = normal
    if mode & op.AO_INSIDE:
        n = (-n[0], -n[1], -n[2])
    s, t = tangents(n)
    row = object_row(geometry.attributes, triangle)
    slot = shader_ray_slot(rays.depth, AO_SLOT)
    free = 0
    for j in range(samples):
        u1, u2 = sample_2d(rays.kind, rays.seed, rays.sample * samples + j, slot)
        x, y, z = cosine_hemisphere(u1, u2)
        d = (x * s[0] + y * t[0] + z * n[0], x * s[1] + y * t[1] + z * n[1], x * s[2] + y * t[2] + z * n[2])
        o = offset_origin(p, ng, d)
        if mode & op.AO_ONLY_LOCAL:
            blocked = _hits_own_object(rays, geometry.attributes, o, d, distance, row)
        else:
            blocked = is_occluded(rays.caster.scene, rays.caster.words, rays.caster.ids, o[0], o[1], o[2], d[0], d[1],
                                  d[2], distance, rays.time)
        if not blocked:
            free += 1
    return free / samples


@kernel
def cubic_pdf(radius, r):
    """Cycles' bevel falloff: 10 (R - r)³ / (π R⁵) within R, a density over the disk (integrates to 1)."""
    if r >= radius:
        return 0.0
    f = radius - r
    return 10.0 * f * f * f / (radius**5 * math.pi)


@kernel
def cubic_radius(radius, xi):
    """The radius of ``cubic_pdf`` at cumulative probability ``xi``: the root of 10x² - 20x³ + 15x⁴ - 4x⁵ = xi
    in [0, 1] by Newton's method (the quintic has no closed form), times ``radius``."""
    x = 0.25
    for _ in range(10):
        x2 = x * x
        x3 = x2 * x
        nx = 1.0 - x
        f = 10.0 * x2 - 20.0 * x3 + 15.0 * x2 * x2 - 4.0 * x2 * x3 - xi
        slope = 20.0 * (x * nx) * (nx * nx)
        if abs(f) < 1e-6 or slope == 0.0:
            break
        x = min(max(x - f / slope, 0.0), 1.0)
    return x * radius


@inlined
def _pick_axis(u, ng, s, t):
    """Cycles' choice of probe axis: the normal half the time, each tangent a quarter. Returns (probe axis,
    disk axes, the three axes' pick probabilities in that order, ``u`` rescaled to [0, 1))."""
    if u < 0.5:
        return ng, s, t, 0.5, 0.25, 0.25, u * 2.0
    if u < 0.75:
        return s, ng, t, 0.25, 0.5, 0.25, (u - 0.5) * 4.0
    return t, s, ng, 0.25, 0.25, 0.5, (u - 0.75) * 4.0


@inlined
def bevel_normal(rays, geometry, triangle, p, ng, n, backfacing, radius, samples):
    """The Bevel node's normal at a hit (``ng`` / ``n`` facing the ray, as the program's); ``n`` where
    nothing is sampled."""
    row = object_row(geometry.attributes, triangle)
    if radius <= 0.0 or samples < 1 or row < 0 or rays.min_pdf < BEVEL_MIN_PDF:
        return (float(n[0]), float(n[1]), float(n[2]))
    ng = (float(ng[0]), float(ng[1]), float(ng[2]))
    s0, t0 = tangents(ng)
    slot = shader_ray_slot(rays.depth, BEVEL_SLOT)
    sx, sy, sz = 0.0, 0.0, 0.0
    for j in range(samples):
        u1, u2 = sample_2d(rays.kind, rays.seed, rays.sample * samples + j, slot)
        axis, da, db, pick_n, pick_a, pick_b, u1 = _pick_axis(u1, ng, s0, t0)
        phi = 2.0 * math.pi * u1
        disk_r = cubic_radius(radius, u2)
        height = math.sqrt(max(radius * radius - disk_r * disk_r, 0.0))
        ca, sa = disk_r * math.cos(phi), disk_r * math.sin(phi)
        origin = (p[0] + axis[0] * height + ca * da[0] + sa * db[0], p[1] + axis[1] * height + ca * da[1] + sa * db[1],
                  p[2] + axis[2] * height + ca * da[2] + sa * db[2])
        direction = (-axis[0], -axis[1], -axis[2])
        disk_pdf = cubic_pdf(radius, disk_r)
        if disk_pdf <= 0.0:
            continue
        travelled = 0.0
        for _ in range(MAX_STEPS):  # every hit on the probe segment, as Cycles' local intersection
            hit, t, hu, hv = closest_hit(rays.caster, origin[0], origin[1], origin[2], direction[0], direction[1],
                                         direction[2], 2.0 * height - travelled, rays.time)
            if hit < 0:
                break
            if object_row(geometry.attributes, hit) == row:
                hp, hng, hns = surface_at(geometry, hit, hu, hv, rays.time)
                pdf_n = pick_n * abs(axis[0] * hng[0] + axis[1] * hng[1] + axis[2] * hng[2])
                pdf_a = pick_a * abs(da[0] * hng[0] + da[1] * hng[1] + da[2] * hng[2])
                pdf_b = pick_b * abs(db[0] * hng[0] + db[1] * hng[1] + db[2] * hng[2])
                denominator = pdf_n * pdf_n + pdf_a * pdf_a + pdf_b * pdf_b
                if denominator > 0.0:
                    r = math.sqrt((hp[0] - p[0]) ** 2 + (hp[1] - p[1]) ** 2 + (hp[2] - p[2]) ** 2)
                    w = pdf_n / denominator * cubic_pdf(radius, r) / disk_pdf
                    sx += w * hns[0]
                    sy += w * hns[1]
                    sz += w * hns[2]
            origin, step = step_past(origin, direction, float(t))
            travelled += step
            if travelled >= 2.0 * height:
                break
    length = math.sqrt(sx * sx + sy * sy + sz * sz)
    if length == 0.0 or not math.isfinite(length):
        return (float(n[0]), float(n[1]), float(n[2]))
    out = (sx / length, sy / length, sz / length)
    return (-out[0], -out[1], -out[2]) if backfacing else out


@kernel
def _unit_or(v, fallback):
    """``v`` made unit length, or ``fallback`` where it has none."""
    length = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if length == 0.0 or not math.isfinite(length):
        return fallback
    return (v[0] / length, v[1] / length, v[2] / length)


@kernel
def ray_time(rays):
    """The ray time of the hit a material runs at: ``rays.time``, or ``FRAME_TIME`` with ``rays`` None (light
    tracing, baking: no motion blur there). A kernel of its own, so that numba compiles it without the rays."""
    if rays is not None:
        return float(rays.time)
    return FRAME_TIME


@kernel
def traced_node(code, mode, dst, a, b, c, regs, rays, geometry, triangle, p, ng, n, backfacing):
    """Run an ``AMBIENT_OCCLUSION`` or ``BEVEL`` instruction (operands as ``opcodes`` describes them). A kernel
    of its own, so that with ``rays`` None (no tracing here) numba compiles it without the rays."""
    if code == op.AMBIENT_OCCLUSION:
        ao = 1.0  # Cycles' value where a shader cannot trace (light sampling, shadow rays)
        if rays is not None:
            n = (float(n[0]), float(n[1]), float(n[2]))
            normal = _unit_or((regs[b], regs[b + 1], regs[b + 2]) if b >= 0 else n, n)
            ao = ambient_occlusion(rays, geometry, triangle, p, ng, normal, regs[a], mode)
        regs[dst] = ao
        regs[dst + 1] = ao * regs[c]
        regs[dst + 2] = ao * regs[c + 1]
        regs[dst + 3] = ao * regs[c + 2]
        return
    n = (float(n[0]), float(n[1]), float(n[2]))
    bevelled = n
    if rays is not None:
        bevelled = bevel_normal(rays, geometry, triangle, p, ng, n, backfacing, regs[a], mode)
        if b >= 0:  # a linked Normal keeps its own detail, moved as the bevel moves the shading normal
            bevelled = _unit_or((regs[b] + bevelled[0] - n[0], regs[b + 1] + bevelled[1] - n[1],
                                 regs[b + 2] + bevelled[2] - n[2]), n)
    regs[dst] = bevelled[0]
    regs[dst + 1] = bevelled[1]
    regs[dst + 2] = bevelled[2]


def traces_rays(material_arrays) -> bool:
    """Whether some material program of ``material_arrays`` (``table.MaterialArrays``) traces rays of its own."""
    codes = material_arrays.programs.instructions[:, op.OP]
    return bool(((codes == op.AMBIENT_OCCLUSION) | (codes == op.BEVEL)).any())
