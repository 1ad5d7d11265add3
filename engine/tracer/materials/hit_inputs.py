"""What a material program can read about the point it shades: interpolated UV maps, colour attributes
and UV tangents (``geometry.SurfaceArrays``), object and texture-space coordinates, object info.

Corner data is interpolated with the hit's barycentrics (corner weights 1 - u - v, u, v). Bump mapping
evaluates heights at the point moved a small step along the surface (``bump_step``): the inputs then read
the moved point (``moved``), so textures see consistent coordinates. Rows past the triangles are spheres
(``spheres``), then curve segments (``curves``): no corner data (UVs, colours and tangents read as on a mesh
without them), (u, v) the normal's code; a sphere's Point Info (``point_info``) comes from ``Geometry.spheres``,
a curve segment's Hair Info (``hair_info``) from its control points and ``Geometry.curve_info``.
"""

from __future__ import annotations

import math

from ..curves import control_point, curve_tangent
from ..geometry import FRAME_TIME, surface_at
from ..jit import inlined, kernel
from ..octahedral import decode
from ..spheres import sphere_at
from ..vec3 import tangents

# ``SurfaceArrays.objects`` columns: world→object affine (row-major 3 x 4, camera offset folded in),
# generated-coordinate scale and offset (object space → 0-1 over the texture space), world location,
# colour RGBA, pass index, random.
O_MATRIX = 0
O_GENERATED_SCALE = 12
O_GENERATED_OFFSET = 15
O_LOCATION = 18
O_COLOR = 21
O_PASS_INDEX = 25
O_RANDOM = 26
OBJECT_ROW = 27

#: Bump steps are this fraction of the distance to the camera (about a tenth of a pixel's footprint
#: at common resolutions, as Blender's bump filter width), never below ``_BUMP_FLOOR_M``.
_BUMP_RELATIVE = 1e-4
_BUMP_FLOOR_M = 1e-7


@inlined
def bump_step(geometry, triangle, p, ng):
    """(dP_x, dP_y): two orthogonal small steps in the triangle's plane (a sphere's tangent plane),
    right-handed about ``ng``."""
    eps = max(_BUMP_RELATIVE * math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), _BUMP_FLOOR_M)
    if triangle >= geometry.triangles.shape[0]:
        tx, ty, tz = tangents(ng)[0]  # any unit vector in the sphere's tangent plane
    else:
        tri = geometry.triangles[triangle]
        vs = geometry.vertices
        ex = float(vs[tri[1], 0]) - float(vs[tri[0], 0])
        ey = float(vs[tri[1], 1]) - float(vs[tri[0], 1])
        ez = float(vs[tri[1], 2]) - float(vs[tri[0], 2])
        n = math.sqrt(ex * ex + ey * ey + ez * ez)
        tx, ty, tz = ex / n, ey / n, ez / n
    bx = ng[1] * tz - ng[2] * ty
    by = ng[2] * tx - ng[0] * tz
    bz = ng[0] * ty - ng[1] * tx
    return (eps * tx, eps * ty, eps * tz), (eps * bx, eps * by, eps * bz)


@inlined
def moved(geometry, triangle, u, v, p, step):
    """Barycentrics and position of the hit moved by ``step`` (in the triangle's plane; on a sphere the
    normal's code stays)."""
    if triangle >= geometry.triangles.shape[0]:
        return u, v, (p[0] + step[0], p[1] + step[1], p[2] + step[2])
    tri = geometry.triangles[triangle]
    vs = geometry.vertices
    a0, a1, a2 = float(vs[tri[0], 0]), float(vs[tri[0], 1]), float(vs[tri[0], 2])
    e1 = (float(vs[tri[1], 0]) - a0, float(vs[tri[1], 1]) - a1, float(vs[tri[1], 2]) - a2)
    e2 = (float(vs[tri[2], 0]) - a0, float(vs[tri[2], 1]) - a1, float(vs[tri[2], 2]) - a2)
    g11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]
    g12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]
    g22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]
    r1 = e1[0] * step[0] + e1[1] * step[1] + e1[2] * step[2]
    r2 = e2[0] * step[0] + e2[1] * step[1] + e2[2] * step[2]
    det = g11 * g22 - g12 * g12
    if not det > 0.0:
        return u, v, p
    du = (g22 * r1 - g12 * r2) / det
    dv = (g11 * r2 - g12 * r1) / det
    return u + du, v + dv, (p[0] + step[0], p[1] + step[1], p[2] + step[2])


@kernel
def corner_uv(uvs, slot, triangle, u, v):
    if slot >= uvs.shape[0] or triangle >= uvs.shape[1]:
        return 0.0, 0.0
    c = uvs[slot, triangle]
    w = 1.0 - u - v
    return (w * float(c[0, 0]) + u * float(c[1, 0]) + v * float(c[2, 0]),
            w * float(c[0, 1]) + u * float(c[1, 1]) + v * float(c[2, 1]))


@kernel
def corner_color(colors, slot, triangle, u, v):
    """(r, g, b, a) of a colour attribute (missing: black, alpha 0 as Blender)."""
    if slot >= colors.shape[0] or triangle >= colors.shape[1]:
        return 0.0, 0.0, 0.0, 0.0
    c = colors[slot, triangle]
    w = 1.0 - u - v
    return (w * float(c[0, 0]) + u * float(c[1, 0]) + v * float(c[2, 0]),
            w * float(c[0, 1]) + u * float(c[1, 1]) + v * float(c[2, 1]),
            w * float(c[0, 2]) + u * float(c[1, 2]) + v * float(c[2, 2]),
            w * float(c[0, 3]) + u * float(c[1, 3]) + v * float(c[2, 3]))


@kernel
def corner_tangent(tangents, slot, triangle, u, v):
    """(interpolated unnormalised tangent, bitangent sign) of UV tangent slot ``slot``."""
    if slot >= tangents.shape[0] or triangle >= tangents.shape[1]:
        return (0.0, 0.0, 0.0), 1.0
    c = tangents[slot, triangle]
    w = 1.0 - u - v
    t = (w * float(c[0, 0]) + u * float(c[1, 0]) + v * float(c[2, 0]),
         w * float(c[0, 1]) + u * float(c[1, 1]) + v * float(c[2, 1]),
         w * float(c[0, 2]) + u * float(c[1, 2]) + v * float(c[2, 2]))
    sign = w * float(c[0, 3]) + u * float(c[1, 3]) + v * float(c[2, 3])
    return t, (-1.0 if sign < 0.0 else 1.0)


@kernel
def object_row(attributes, triangle):
    """Row of ``attributes.objects`` for the instance ``triangle`` belongs to, or -1."""
    if attributes.instance.shape[0] <= triangle:
        return -1
    return attributes.instance[triangle]


@kernel
def object_point(attributes, triangle, u, v, row, p):
    """The hit in its instance's object space: the interpolated object-space corners when exported, else
    camera-relative ``p`` through the world→object transform (world space without objects)."""
    positions = attributes.positions
    if positions.shape[0] > triangle:
        c = positions[triangle]
        w = 1.0 - u - v
        return (w * float(c[0, 0]) + u * float(c[1, 0]) + v * float(c[2, 0]),
                w * float(c[0, 1]) + u * float(c[1, 1]) + v * float(c[2, 1]),
                w * float(c[0, 2]) + u * float(c[1, 2]) + v * float(c[2, 2]))
    offset = attributes.offset
    if row < 0:
        return (p[0] + offset[0], p[1] + offset[1], p[2] + offset[2])
    m = attributes.objects[row]
    return (m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3], m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
            m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11])


@kernel
def generated(objects, row, p_object):
    if row < 0:
        return p_object
    m = objects[row]
    return (p_object[0] * m[O_GENERATED_SCALE] + m[O_GENERATED_OFFSET],
            p_object[1] * m[O_GENERATED_SCALE + 1] + m[O_GENERATED_OFFSET + 1],
            p_object[2] * m[O_GENERATED_SCALE + 2] + m[O_GENERATED_OFFSET + 2])


@inlined
def raw_normal(geometry, triangle, u, v):
    """The interpolated corner normal, unnormalised and not flipped (the geometric normal when flat; a
    sphere's outward normal; a curve's shading normal)."""
    if triangle >= geometry.triangles.shape[0] + geometry.spheres.shape[0]:
        return surface_at(geometry, triangle, u, v, FRAME_TIME)[2]
    if triangle >= geometry.triangles.shape[0]:
        return decode(u, v)
    if geometry.normals.shape[0] == 0:
        tri = geometry.triangles[triangle]
        vs = geometry.vertices
        e1 = (float(vs[tri[1], 0]) - float(vs[tri[0], 0]), float(vs[tri[1], 1]) - float(vs[tri[0], 1]),
              float(vs[tri[1], 2]) - float(vs[tri[0], 2]))
        e2 = (float(vs[tri[2], 0]) - float(vs[tri[0], 0]), float(vs[tri[2], 1]) - float(vs[tri[0], 1]),
              float(vs[tri[2], 2]) - float(vs[tri[0], 2]))
        nx = e1[1] * e2[2] - e1[2] * e2[1]
        ny = e1[2] * e2[0] - e1[0] * e2[2]
        nz = e1[0] * e2[1] - e1[1] * e2[0]
        n = math.sqrt(nx * nx + ny * ny + nz * nz)
        return (nx / n, ny / n, nz / n)
    w = 1.0 - u - v
    cn = geometry.normals[triangle]
    return (w * cn[0, 0] + u * cn[1, 0] + v * cn[2, 0], w * cn[0, 1] + u * cn[1, 1] + v * cn[2, 1],
            w * cn[0, 2] + u * cn[1, 2] + v * cn[2, 2])


@inlined
def point_info(geometry, triangle, field, time):
    """Cycles' Point Info on sphere row ``triangle``, ``field`` as ``opcodes.POINT_INFO_FIELDS``: 0 its centre
    (camera-relative, where it stands at ray time ``time``, as Cycles interpolates it), 1 its radius (the frame's,
    as Cycles reads it) or 2 its random number, the scalars in the first of three; zeros on triangles and curves,
    as on a mesh in Blender."""
    s = triangle - geometry.triangles.shape[0]
    if s < 0 or s >= geometry.spheres.shape[0]:
        return 0.0, 0.0, 0.0
    if field == 0:
        x, y, z, _ = sphere_at(geometry, s, time)
        return x, y, z
    if field == 1:
        return float(geometry.spheres[s, 3]), 0.0, 0.0
    return float(geometry.sphere_random[s]), 0.0, 0.0


@inlined
def hair_info(geometry, triangle, u, wo, field, time):
    """Cycles' Hair Info output ``field`` (``opcodes.HAIR_INFO_FIELDS``) at curve parameter ``u`` of the segment in
    row ``triangle`` seen along ``wo``, as a 3-tuple (scalars in its first entry); zeros off curves, as Cycles
    finds no curve attribute there (``svm_node_hair_info``, ``geom/curve.h``). Intercept is interpolated linearly
    between the segment's points, Thickness is twice the radius interpolated so, Tangent Normal is the view
    direction made perpendicular to the tangent (the strand as it stands at ray time ``time``)."""
    first = geometry.triangles.shape[0] + geometry.spheres.shape[0]
    s = triangle - first
    if s < 0 or s >= geometry.curve_segments.shape[0]:
        return (0.0, 0.0, 0.0)
    if field == 0:
        return (1.0, 0.0, 0.0)
    if field == 4:
        t = curve_tangent(geometry, s, u, time)
        t2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2]
        along = (t[0] * wo[0] + t[1] * wo[1] + t[2] * wo[2]) / t2 if t2 > 0.0 else 0.0
        x, y, z = wo[0] - along * t[0], wo[1] - along * t[1], wo[2] - along * t[2]
        size = math.sqrt(x * x + y * y + z * z)
        return (x / size, y / size, z / size) if size > 0.0 else (0.0, 0.0, 0.0)
    if field == 3:
        k = geometry.curve_segments[s]
        r0, r1 = control_point(geometry, k + 1, time)[3], control_point(geometry, k + 2, time)[3]
        return (2.0 * ((r1 - r0) * u + r0), 0.0, 0.0)
    info = geometry.curve_info
    if info.shape[0] <= s:
        return (0.0, 0.0, 0.0)
    if field == 1:
        return ((1.0 - u) * float(info[s, 0]) + u * float(info[s, 1]), 0.0, 0.0)
    return (float(info[s, 2 if field == 2 else 3]), 0.0, 0.0)
