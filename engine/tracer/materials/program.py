"""The interpreter of material programs: one compiled loop over a material's instructions, per hit.

A program (``materials.opcodes``) reads the hit (UVs, attributes, position, normals, the view direction),
runs Blender's node semantics (``nodes``, ``textures``) on a register file and writes its results into
the registers the closures read (spectral parameters, emission, the shading normal) or straight into
the closure rows (``BIND``: roughness, IOR, weights). The register file starts from the material's
constants (``ProgramArrays.constants``); nothing is allocated.

Hit inputs take a *variant* (operand g): 0 reads the hit itself, 1 and 2 the hit moved a small step
along the surface (``hit_inputs.bump_step``), for the height samples of Bump nodes.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..bsdf.optics import fresnel_dielectric  # Blender's Fresnel node: the exact unpolarised reflectance
from ..bsdf.sheen import ltc_fit
from ..jit import inlined, kernel
from ..node_eval import colour as col
from ..node_eval import math as nmath
from ..node_eval import vector as vec
from ..textures.image import image_lookup
from ..textures.noise import noise_texture
from ..textures.patterns import brick, checker, gradient, magic, wave, white_noise
from ..textures.voronoi import voronoi_texture
from . import hit_inputs as hit
from . import opcodes as op
from .closure_normals import valid_specular_normal
from .layering import dielectric_darkening, dielectric_s
from .light_path import light_path_output
from .shader_rays import ray_time, traced_node

#: Per material: instruction range ``start`` / ``count``, register-file range ``const_start`` /
#: ``const_count`` in ``constants``; ``normal``, ``emission`` (colour) and ``emission_scale`` registers (-1:
#: none); ``instructions`` int32 [N, INSTRUCTION]; ``constants`` float64 [C]; ``tables``
#: (``layering.LayerTables``).
ProgramArrays = namedtuple("ProgramArrays", "start count const_start const_count normal emission emission_scale "
                                            "instructions constants tables")


@kernel
def _v3(regs, r):
    return (regs[r], regs[r + 1], regs[r + 2])


@kernel
def _put3(regs, r, v):
    regs[r] = v[0]
    regs[r + 1] = v[1]
    regs[r + 2] = v[2]


@kernel
def _optional3(regs, r, fallback):
    return (regs[r], regs[r + 1], regs[r + 2]) if r >= 0 else fallback


@kernel
def run_program(instructions, first, count, regs, rows, tables, textures, geometry, triangle, u, v, p, ng, n, wo,
                backfacing, rays):
    """Run instructions ``first .. first + count`` for the hit at barycentrics (u, v) of ``triangle``:
    ``p`` camera-relative point, ``ng`` / ``n`` geometric and shading normals facing ``wo`` (unit, towards
    where the ray came from), ``backfacing`` whether the ray arrived on the back of the surface. ``rays``: a
    ``shader_rays.ShaderRays`` where the material may trace (a ray's hit), else None (compiled without)."""
    attrs = geometry.attributes
    step_x, step_y = hit.bump_step(geometry, triangle, p, ng)
    for index in range(first, first + count):
        ins = instructions[index]
        code = ins[op.OP]
        mode = ins[op.MODE]
        dst = ins[op.DST]
        a, b, c, d, e, f, g = ins[3], ins[4], ins[5], ins[6], ins[7], ins[8], ins[9]
        if code == op.EXTRA:
            continue
        if code == op.LIGHT_PATH:
            regs[dst] = light_path_output(regs, mode)
            continue
        if code == op.AMBIENT_OCCLUSION or code == op.BEVEL:
            traced_node(code, mode, dst, a, b, c, regs, rays, geometry, triangle, p, ng, n, backfacing)
            continue
        if code <= op.HAIR_INFO:
            hu, hv, hp = u, v, p
            if g == 1:
                hu, hv, hp = hit.moved(geometry, triangle, u, v, p, step_x)
            elif g == 2:
                hu, hv, hp = hit.moved(geometry, triangle, u, v, p, step_y)
            if code == op.UV:
                s, t = hit.corner_uv(attrs.uvs, a, triangle, hu, hv)
                _put3(regs, dst, (s, t, 0.0))
            elif code == op.COLOR_ATTRIBUTE:
                cr, cg, cb, ca = hit.corner_color(attrs.colors, a, triangle, hu, hv)
                _put3(regs, dst, (cr, cg, cb))
                regs[dst + 3] = ca
            elif code == op.POSITION:
                _put3(regs, dst, (hp[0] + attrs.offset[0], hp[1] + attrs.offset[1], hp[2] + attrs.offset[2]))
            elif code == op.NORMAL:
                _put3(regs, dst, n)
            elif code == op.TRUE_NORMAL:
                _put3(regs, dst, ng)
            elif code == op.INCOMING:
                _put3(regs, dst, wo)
            elif code == op.BACKFACING:
                regs[dst] = 1.0 if backfacing else 0.0
            elif code == op.PARAMETRIC:
                _put3(regs, dst, (1.0 - hu - hv, hu, 0.0))
            elif code == op.POINT_INFO:
                info = hit.point_info(geometry, triangle, mode, ray_time(rays))
                if mode == 0:  # Position: world
                    _put3(regs, dst, (info[0] + attrs.offset[0], info[1] + attrs.offset[1], info[2] + attrs.offset[2]))
                else:
                    regs[dst] = info[0]
            elif code == op.HAIR_INFO:
                info = hit.hair_info(geometry, triangle, hu, wo, mode, ray_time(rays))
                if mode == 4:  # Tangent Normal
                    _put3(regs, dst, info)
                else:
                    regs[dst] = info[0]
            elif code == op.TANGENT:
                t3, _ = hit.corner_tangent(attrs.tangents, a, triangle, hu, hv)
                length = math.sqrt(t3[0] * t3[0] + t3[1] * t3[1] + t3[2] * t3[2])
                _put3(regs, dst, (t3[0] / length, t3[1] / length, t3[2] / length) if length > 0.0 else t3)
            else:
                row = hit.object_row(attrs, triangle)
                if code == op.OBJECT_INFO:
                    if row < 0:
                        _put3(regs, dst, (0.0, 0.0, 0.0))
                    elif mode == 0:
                        o = attrs.objects[row]
                        _put3(regs, dst, (o[hit.O_LOCATION], o[hit.O_LOCATION + 1], o[hit.O_LOCATION + 2]))
                    elif mode == 1:
                        o = attrs.objects[row]
                        _put3(regs, dst, (o[hit.O_COLOR], o[hit.O_COLOR + 1], o[hit.O_COLOR + 2]))
                    elif mode == 2:
                        regs[dst] = attrs.objects[row, hit.O_COLOR + 3]
                    elif mode == 3:
                        regs[dst] = attrs.objects[row, hit.O_PASS_INDEX]
                    else:
                        regs[dst] = attrs.objects[row, hit.O_RANDOM]
                else:
                    po = hit.object_point(attrs, triangle, hu, hv, row, hp)
                    if code == op.GENERATED:
                        po = hit.generated(attrs.objects, row, po)
                    _put3(regs, dst, po)
        elif code == op.COPY:
            for k in range(mode):
                regs[dst + k] = regs[a + k]
        elif code == op.MATH:
            regs[dst] = nmath.math_operation(mode, regs[a], regs[b], regs[c] if c >= 0 else 0.0)
        elif code == op.VECTOR_MATH:
            zero = (0.0, 0.0, 0.0)
            out, scalar = nmath.vector_math(mode, _v3(regs, a), _optional3(regs, b, zero), _optional3(regs, c, zero),
                                            regs[d] if d >= 0 else 1.0)
            if mode == 10 or mode == 11 or mode == 12:
                regs[dst] = scalar
            else:
                _put3(regs, dst, out)
        elif code == op.MIX_FLOAT:
            t = regs[a]
            if mode:
                t = min(max(t, 0.0), 1.0)
            regs[dst] = regs[b] * (1.0 - t) + regs[c] * t
        elif code == op.MIX_VECTOR:
            for k in range(3):
                t = regs[a + k] if mode else regs[a]
                if e == 1:
                    t = min(max(t, 0.0), 1.0)
                regs[dst + k] = regs[b + k] * (1.0 - t) + regs[c + k] * t
        elif code == op.MIX_COLOR:
            t = regs[a]
            if d == 1:
                t = min(max(t, 0.0), 1.0)
            out = col.blend(mode, t, _v3(regs, b), _v3(regs, c))
            if e == 1:
                out = (min(max(out[0], 0.0), 1.0), min(max(out[1], 0.0), 1.0), min(max(out[2], 0.0), 1.0))
            _put3(regs, dst, out)
        elif code == op.MAP_RANGE:
            regs[dst] = nmath.map_range(mode, regs[a], regs[b], regs[c], regs[d], regs[e], regs[f], g == 1)
        elif code == op.CLAMP:
            regs[dst] = nmath.clamp_value(mode, regs[a], regs[b], regs[c])
        elif code == op.RGB_TO_BW:
            regs[dst] = col.luminance(_v3(regs, a))
        elif code == op.SEPARATE_COLOR:
            colour = _v3(regs, a)
            if mode == 1:
                colour = col.rgb_to_hsv(colour)
            elif mode == 2:
                colour = col.rgb_to_hsl(colour)
            _put3(regs, dst, colour)
        elif code == op.COMBINE_COLOR:
            colour = (regs[a], regs[b], regs[c])
            if mode == 1:
                colour = col.hsv_to_rgb(colour)
            elif mode == 2:
                colour = col.hsl_to_rgb(colour)
            _put3(regs, dst, colour)
        elif code == op.HUE_SATURATION:
            _put3(regs, dst, col.hue_saturation_value(regs[a], regs[b], regs[c], regs[d], _v3(regs, e)))
        elif code == op.INVERT:
            _put3(regs, dst, col.invert(regs[a], _v3(regs, b)))
        elif code == op.BRIGHT_CONTRAST:
            _put3(regs, dst, col.bright_contrast(_v3(regs, a), regs[b], regs[c]))
        elif code == op.GAMMA:
            _put3(regs, dst, col.gamma(_v3(regs, a), regs[b]))
        elif code == op.COLOR_RAMP:
            for k in range(4):
                regs[dst + k] = col.table_lookup(regs, b, c, 4, k, regs[a], mode == 0, False)
        elif code == op.CURVES:
            lo = regs[f]
            span = regs[f + 1] - lo
            if mode == 2:
                x = (regs[b] - lo) / span if span != 0.0 else 0.0
                regs[dst] = col.table_lookup(regs, c, d, 3, 0, x, True, e == 1)
            else:
                fac = regs[a] if a >= 0 else 1.0
                for k in range(3):
                    value = regs[b + k]
                    x = (value - lo) / span if span != 0.0 else 0.0
                    curved = col.table_lookup(regs, c, d, 3, k, x, True, e == 1)
                    regs[dst + k] = (1.0 - fac) * value + fac * curved
        elif code == op.MAPPING:
            _put3(regs, dst, vec.mapping(mode, _v3(regs, a), _v3(regs, b), _v3(regs, c), _v3(regs, d)))
        elif code == op.VECTOR_ROTATE:
            _put3(regs, dst, vec.vector_rotate(mode, _v3(regs, a), _v3(regs, b), _v3(regs, c), regs[d],
                                               _v3(regs, e), f == 1))
        elif code == op.COMBINE_XYZ:
            _put3(regs, dst, (regs[a], regs[b], regs[c]))
        elif code == op.FLOAT_TO_COLOR:
            _put3(regs, dst, (regs[a], regs[a], regs[a]))
        elif code == op.VECTOR_TO_FLOAT:
            regs[dst] = (regs[a] + regs[a + 1] + regs[a + 2]) / 3.0
        elif code == op.FRESNEL:
            normal = _optional3(regs, b, n)
            cos = wo[0] * normal[0] + wo[1] * normal[1] + wo[2] * normal[2]
            eta = max(regs[a], 1e-5)
            regs[dst] = fresnel_dielectric(abs(cos), 1.0 / eta if backfacing else eta)
        elif code == op.LAYER_WEIGHT:
            normal = _optional3(regs, b, n)
            cos = wo[0] * normal[0] + wo[1] * normal[1] + wo[2] * normal[2]
            blend = regs[a]
            eta = max(1.0 - blend, 1e-5)
            regs[dst] = fresnel_dielectric(abs(cos), eta if backfacing else 1.0 / eta)
            facing = abs(cos)
            if blend != 0.5:
                blend = min(max(blend, 0.0), 1.0 - 1e-5)
                blend = 2.0 * blend if blend < 0.5 else 0.5 / (1.0 - blend)
                facing = facing**blend
            regs[dst + 1] = 1.0 - facing
        elif code == op.NORMAL_MAP:
            _put3(regs, dst, _normal_map(mode, regs[a], _v3(regs, b), c, attrs, geometry, triangle, u, v, n,
                                         backfacing))
        elif code == op.VALID_REFLECTION:
            m = _v3(regs, a)
            length = math.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])
            if length > 0.0:
                m = (m[0] / length, m[1] / length, m[2] / length)
                if m[0] * ng[0] + m[1] * ng[1] + m[2] * ng[2] < 1.0 - 1e-7:
                    m = valid_specular_normal(ng, wo, m)
            _put3(regs, dst, m)
        elif code == op.BUMP:
            distance = -regs[e] if mode == 1 else regs[e]
            _put3(regs, dst, vec.bump_normal(_optional3(regs, f, n), step_x, step_y, regs[a], regs[b], regs[c],
                                             regs[d], distance))
        elif code == op.IMAGE:
            rgba = image_lookup(textures, b, regs[a], regs[a + 1])
            _put3(regs, dst, (rgba[0], rgba[1], rgba[2]))
            regs[dst + 3] = rgba[3]
        elif code == op.NOISE:
            extra = instructions[index + 1]
            dims = mode & 7
            scale = regs[c]
            q = (regs[a] * scale, regs[a + 1] * scale, regs[a + 2] * scale, regs[b] * scale)
            if dims == 1:
                q = (q[3], 0.0, 0.0, 0.0)
            fac, r, gg, bb = noise_texture(mode >> 3, dims, q, regs[d], regs[e], regs[f], regs[extra[3]],
                                           regs[extra[4]], regs[g], extra[5] == 1, extra[6] == 1)
            regs[dst] = fac
            _put3(regs, dst + 1, (r, gg, bb))
        elif code == op.VORONOI:
            extra = instructions[index + 1]
            dist, colour, position, radius = voronoi_texture(
                mode & 7, (mode >> 6) & 7, (mode >> 3) & 7, _v3(regs, a), regs[c], regs[d], regs[e], regs[f],
                regs[g], regs[extra[3]], regs[extra[4]], extra[5] == 1)
            regs[dst] = dist
            _put3(regs, dst + 1, colour)
            _put3(regs, dst + 4, position)
            regs[dst + 7] = 0.0
            regs[dst + 8] = radius
        elif code == op.CHECKER:
            scale = regs[d]
            fac = checker((regs[a] * scale, regs[a + 1] * scale, regs[a + 2] * scale))
            _put3(regs, dst, _v3(regs, b) if fac == 1.0 else _v3(regs, c))
            regs[dst + 3] = fac
        elif code == op.GRADIENT:
            fac = gradient(mode, _v3(regs, a))
            _put3(regs, dst, (fac, fac, fac))
            regs[dst + 3] = fac
        elif code == op.WAVE:
            scale = regs[b]
            fac = wave(mode >> 4, (mode >> 2) & 3, mode & 3, (regs[a] * scale, regs[a + 1] * scale,
                                                               regs[a + 2] * scale), regs[c], regs[d], regs[e],
                       regs[f], regs[g])
            _put3(regs, dst, (fac, fac, fac))
            regs[dst + 3] = fac
        elif code == op.BRICK:
            extra = instructions[index + 1]
            scale = regs[e]
            tint, mortar = brick((regs[a] * scale, regs[a + 1] * scale, regs[a + 2] * scale), regs[f], regs[g],
                                 regs[extra[3]], regs[extra[4]], regs[extra[5]], regs[extra[6]], extra[7],
                                 regs[extra[8]], extra[9])
            c1 = _v3(regs, b)
            if mortar != 1.0:
                c2 = _v3(regs, c)
                c1 = ((1.0 - tint) * c1[0] + tint * c2[0], (1.0 - tint) * c1[1] + tint * c2[1],
                      (1.0 - tint) * c1[2] + tint * c2[2])
            m = _v3(regs, d)
            _put3(regs, dst, (c1[0] * (1.0 - mortar) + m[0] * mortar, c1[1] * (1.0 - mortar) + m[1] * mortar,
                              c1[2] * (1.0 - mortar) + m[2] * mortar))
            regs[dst + 3] = mortar
        elif code == op.MAGIC:
            colour = magic(_v3(regs, a), regs[b], mode, regs[c])
            _put3(regs, dst, colour)
            regs[dst + 3] = (colour[0] + colour[1] + colour[2]) / 3.0
        elif code == op.WHITE_NOISE:
            value, r, gg, bb = white_noise(mode, _v3(regs, a), regs[b])
            regs[dst] = value
            _put3(regs, dst + 1, (r, gg, bb))
        elif code == op.LAYER_ALBEDO:
            regs[dst] = dielectric_s(tables, regs[a], regs[b], regs[c])
        elif code == op.LAYER_DARKENING:
            regs[dst] = dielectric_darkening(tables, regs[a], regs[b], regs[c], regs[d])
        elif code == op.SHEEN_ALBEDO:
            regs[dst] = ltc_fit(tables.sheen, regs[a], abs(regs[b]))[2]
        elif code == op.BIND:
            if mode == 1:
                rows[a, b] *= regs[c]
            else:
                rows[a, b] = regs[c]
        elif code == op.BIND_RGB:
            rows[a, b] = -2.0 - c


@kernel
def _normal_map(space, strength, colour, slot, attrs, geometry, triangle, u, v, n, backfacing):
    if space == 0:
        tangent, sign = hit.corner_tangent(attrs.tangents, slot, triangle, u, v)
        if tangent[0] == 0.0 and tangent[1] == 0.0 and tangent[2] == 0.0:
            return n
        normal = hit.raw_normal(geometry, triangle, u, v)
        out = vec.tangent_normal_map(colour, strength, normal, tangent, sign)
        return (-out[0], -out[1], -out[2]) if backfacing else out
    m = (2.0 * (colour[0] - 0.5), 2.0 * (colour[1] - 0.5), 2.0 * (colour[2] - 0.5))
    if space == 3 or space == 4:
        m = (m[0], -m[1], -m[2])
    if space == 1 or space == 3:
        m = _object_normal(attrs, triangle, m)
    length = math.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])
    if length > 0.0:
        m = (m[0] / length, m[1] / length, m[2] / length)
    if backfacing:
        m = (-m[0], -m[1], -m[2])
    if strength != 1.0:
        s = max(strength, 0.0)
        m = (n[0] + (m[0] - n[0]) * s, n[1] + (m[1] - n[1]) * s, n[2] + (m[2] - n[2]) * s)
        length = math.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])
        if length > 0.0:
            m = (m[0] / length, m[1] / length, m[2] / length)
    if m[0] == 0.0 and m[1] == 0.0 and m[2] == 0.0:
        return n
    return m


@kernel
def _object_normal(attrs, triangle, m):
    """An object-space normal in world space: the inverse transpose of object→world, i.e. the transpose of
    the stored world→object matrix."""
    row = hit.object_row(attrs, triangle)
    if row < 0:
        return m
    o = attrs.objects[row]
    return (o[0] * m[0] + o[4] * m[1] + o[8] * m[2], o[1] * m[0] + o[5] * m[1] + o[9] * m[2],
            o[2] * m[0] + o[6] * m[1] + o[10] * m[2])
