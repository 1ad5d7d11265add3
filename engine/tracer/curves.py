"""Curves: the strands of Blender's Hair Curves objects, as round tubes (Cycles' "3D Curves" shape).

The export fills ``scene.Scene.curves`` (a ``CurveSegments``, world space, float64): every strand's points
with its first and last point repeated once, so each segment has the 4 control points of a uniform
Catmull-Rom spline (through the 2nd and 3rd) that Embree's round Catmull-Rom curves and Cycles' thick
curves use. ``camera_relative`` turns them into the float32 table Embree and the kernels share
(``Geometry.curves`` [P, 4]: point minus the render's origin, radius; ``Geometry.curve_segments`` [C]: the
first control point of each segment). Segments are rows of the render's primitives after the triangles and
the spheres: row T + S + c is segment c, so ``Geometry.material``, ``flags`` (and the instance of each row)
hold T + S + C entries and every stage reads a segment's material as it reads a triangle's.

A hit keeps the curve parameter u of the segment (0..1, Embree's) and, in v, the angle around the curve's
tangent at u of the direction from the curve's centre to the hit (``hit_code``). Embree's u is the
parameter whose normal plane holds the hit, at the interpolated radius from the centre (checked on bent,
tapered strands: |hit - C(u)| = r(u) within 4e-7 m, (hit - C(u)) . C'(u) = 0), so ``curve_surface``
rebuilds the hit as C(u) + r(u) times that direction. The normal (geometric and shading alike, as Cycles
takes a thick curve's N and Ng alike) is the tube's own, Embree's Ng: that direction leaning along the
tangent where the radius changes (by -r'/|C'|). Cycles' N = normalize(P - C(u)) does not lean; for hair
(a radius of 0.1 mm falling to 0 over centimetres) the two differ by about 0.1 degree. Curves are not sampled as
lights.

With motion blur ``Geometry.curve_motion`` holds the control points at the shutter's S time steps (``motion``),
which Embree interpolates linearly by ray time; every function here reads a segment's control points at the
ray's ``time`` the same way (``control_point``), so a hit's code, its surface and the way out of the tube are
those of the strand where the ray met it. ``time`` < 0 (``geometry.FRAME_TIME``) or no motion reads the frame's.
The functions take ``strands``, a record with ``curves``, ``curve_segments`` and ``curve_motion``
(``geometry.Geometry``, ``embree.queries.RayCaster``, ``Strands``). The strands' colour attributes and UV maps
(``CurveSegments.colors``, ``uvs``) become rows of the per-corner tables after the triangles' and the spheres'
(``corner_rows``).
"""

from __future__ import annotations

import math
from collections import namedtuple
from dataclasses import dataclass

import numpy as np

from .jit import inlined, kernel
from .time_steps import row_at
from .vec3 import tangents


@dataclass
class CurveSegments:
    """``points`` float64 [P, 3] (world, m) and ``radii`` float64 [P] (m): the control points, each strand's
    ends repeated; ``segments`` int64 [C] (first of the 4 control points of each segment), ``material``
    int32 [C] (index into ``Scene.materials``), ``object`` int32 [C] (index into ``Scene.object_names``),
    ``instance`` int32 [C] (row of ``Scene.surface.instances``; None when no material reads it) and
    ``pass_index`` float32 [C] (Object ▸ Relations ▸ Pass Index; None: 0)."""

    points: np.ndarray
    radii: np.ndarray
    segments: np.ndarray
    material: np.ndarray
    object: np.ndarray
    instance: np.ndarray | None = None
    pass_index: np.ndarray | None = None
    info: np.ndarray | None = None  # float32 [C, 4]: Hair Info per segment (``export.hair_info``); None: zeros
    #: float32 [A, C, 2, 4]: the colour attributes node materials read (slots as ``SurfaceAttributes.colors``),
    #: RGBA at each segment's two points; None: none (they read black, alpha 0)
    colors: np.ndarray | None = None
    #: float32 [S, C, 2, 2]: the UV maps they read (slots as ``SurfaceAttributes.uvs``); None: none (UV (0, 0))
    uvs: np.ndarray | None = None

    def __len__(self) -> int:
        return int(len(self.segments))


def no_curves() -> tuple[np.ndarray, np.ndarray]:
    """(``Geometry.curves``, ``Geometry.curve_segments``) of a render without hair."""
    return np.zeros((0, 4), np.float32), np.zeros(0, np.int32)


def no_curve_motion() -> np.ndarray:
    """``Geometry.curve_motion`` of a render whose strands do not move: empty, so kernels read the frame's."""
    return np.zeros((0, 0, 4), np.float32)


#: The tables the curve functions below read, on their own (``geometry.Geometry`` and ``embree.queries.RayCaster``
#: carry the same fields).
Strands = namedtuple("Strands", "curves curve_segments curve_motion", defaults=(no_curve_motion(),))


def curve_count(curves: CurveSegments | None) -> int:
    """How many segments render (all of them: the export keeps finite strands only)."""
    return 0 if curves is None else len(curves)


def curve_info(curves: CurveSegments | None) -> np.ndarray:
    """``Geometry.curve_info`` float32 [C, 4]: each segment's Hair Info (the intercepts at its two points, its
    strand's length (m, object space) and random number); zeros where the export gave none."""
    if curves is None or not len(curves):
        return np.zeros((0, 4), np.float32)
    if curves.info is None:
        return np.zeros((len(curves), 4), np.float32)
    return np.ascontiguousarray(curves.info, np.float32).reshape(len(curves), 4)


def corner_rows(ends) -> np.ndarray:
    """float32 [A, C, 3, W]: each segment's values at its two ends (``CurveSegments.colors`` or ``uvs``, [A, C, 2,
    W]) as the corners of a triangle (its start, its end, its start again), so that the kernels' corner lookups
    (``hit_inputs.corner_color``, ``corner_uv``) with a hit's (u, v) give (1 - u) start + u end, linear along the
    segment as Cycles interpolates curve-key attributes, whatever the angle in v."""
    return np.ascontiguousarray(np.asarray(ends, np.float32)[:, :, [0, 1, 0]])


def camera_relative(curves: CurveSegments | None, offset) -> tuple[np.ndarray, np.ndarray]:
    """(float32 [P, 4]: control point - ``offset`` (subtracted in float64), radius; int32 [C] segments)."""
    if curves is None or not len(curves):
        return no_curves()
    table = np.empty((len(curves.radii), 4), np.float64)
    table[:, :3] = np.asarray(curves.points, np.float64) - np.asarray(offset, np.float64)
    table[:, 3] = np.asarray(curves.radii, np.float64)
    return np.ascontiguousarray(table.astype(np.float32)), np.ascontiguousarray(curves.segments, np.int32)


def camera_relative_motion(curves: CurveSegments | None, steps, offset) -> np.ndarray:
    """``Geometry.curve_motion``: float32 [S, P, 4] of the control points at the shutter's time steps ``steps``
    (``motion.Motion.curves``, world) minus ``offset`` (in float64), radius; empty where they do not move."""
    if curves is None or not len(curves) or steps is None:
        return no_curve_motion()
    table = np.array(steps, np.float64)
    table[..., :3] -= np.asarray(offset, np.float64)
    return np.ascontiguousarray(table.astype(np.float32))


def moving_segments(curve_motion: np.ndarray, segments: np.ndarray) -> int:
    """How many segments have a control point that moves over the shutter's time steps ``curve_motion``
    (``Geometry.curve_motion``)."""
    if curve_motion.shape[0] < 2 or not len(segments):
        return 0
    moving = ~(curve_motion == curve_motion[:1]).all(axis=(0, 2))
    touched = np.zeros(len(segments), bool)
    for k in range(4):
        touched |= moving[np.asarray(segments, np.int64) + k]
    return int(touched.sum())


def padded_strands(points: np.ndarray, radii: np.ndarray, offsets: np.ndarray):
    """(points [P + 2 N, 3], radii [P + 2 N], segments int64 [P - N]) of N strands (strand k holds
    ``points[offsets[k]:offsets[k + 1]]``, at least 2 each) with each strand's first and last point
    repeated, and the first control point of each of its segments."""
    offsets = np.asarray(offsets, np.int64)
    counts = np.diff(offsets)
    strand = np.repeat(np.arange(len(counts)), counts)
    at = np.arange(len(points)) + 2 * strand + 1  # each point's place in the padded table
    padded = np.empty((len(points) + 2 * len(counts), 3))
    padded_radii = np.empty(len(padded))
    padded[at], padded_radii[at] = points, radii
    first, last = offsets[:-1], offsets[1:] - 1
    padded[at[first] - 1], padded_radii[at[first] - 1] = points[first], radii[first]
    padded[at[last] + 1], padded_radii[at[last] + 1] = points[last], radii[last]
    is_last = np.zeros(len(points), bool)
    is_last[last] = True
    segments = at[~is_last] - 1
    return padded, padded_radii, segments.astype(np.int64)


@kernel
def _weights(u):
    """Uniform Catmull-Rom weights of the 4 control points at ``u``, and of the derivative d/du."""
    u2 = u * u
    u3 = u2 * u
    w = (0.5 * (-u3 + 2.0 * u2 - u), 0.5 * (3.0 * u3 - 5.0 * u2 + 2.0), 0.5 * (-3.0 * u3 + 4.0 * u2 + u),
         0.5 * (u3 - u2))
    d = (0.5 * (-3.0 * u2 + 4.0 * u - 1.0), 0.5 * (9.0 * u2 - 10.0 * u), 0.5 * (-9.0 * u2 + 8.0 * u + 1.0),
         0.5 * (3.0 * u2 - 2.0 * u))
    return w, d


@inlined
def control_point(strands, k, time):
    """(x, y, z, radius) of control point ``k`` at ray time ``time`` (0..1 over the shutter): linear between the two
    time steps around it, as Embree interpolates them; the frame's where nothing moves or ``time`` < 0."""
    return row_at(strands.curves, strands.curve_motion, k, time)


@kernel
def curve_at(strands, c, u, time):
    """(centre (x, y, z), radius, d centre / du, d radius / du) of segment ``c`` at parameter ``u``, ray time
    ``time``."""
    k = strands.curve_segments[c]
    w, d = _weights(u)
    x = y = z = r = dx = dy = dz = dr = 0.0
    for i in range(4):
        px, py, pz, pr = control_point(strands, k + i, time)
        x += w[i] * px
        y += w[i] * py
        z += w[i] * pz
        r += w[i] * pr
        dx += d[i] * px
        dy += d[i] * py
        dz += d[i] * pz
        dr += d[i] * pr
    return (x, y, z), r, (dx, dy, dz), dr


@kernel
def _frame(strands, c, tangent, time):
    """(unit tangent, s, t, |tangent|): a right-handed frame around the curve's tangent at a point of segment
    ``c``. s is a vector fixed for the whole segment (across its chord, the control points 2 to 3), made
    perpendicular to the tangent: the frame then turns smoothly along the segment and does not hang on the
    rounding of the tangent (whose components cancel to noise along a straight strand, and round
    differently where the kernels compute it), so a hit's code and its surface agree."""
    k = strands.curve_segments[c]
    ax, ay, az, _ = control_point(strands, k + 1, time)
    bx, by, bz, _ = control_point(strands, k + 2, time)
    cx, cy, cz = bx - ax, by - ay, bz - az
    chord = math.sqrt(cx * cx + cy * cy + cz * cz)
    length = math.sqrt(tangent[0] * tangent[0] + tangent[1] * tangent[1] + tangent[2] * tangent[2])
    if length > 0.0:
        n = (tangent[0] / length, tangent[1] / length, tangent[2] / length)
    elif chord > 0.0:
        n = (cx / chord, cy / chord, cz / chord)
    else:
        n = (0.0, 0.0, 1.0)
    reference = (cx / chord, cy / chord, cz / chord) if chord > 0.0 else n
    w, w2 = tangents(reference)
    along = w[0] * n[0] + w[1] * n[1] + w[2] * n[2]
    if abs(along) > 0.9:  # a segment bent by more than a right angle: its other fixed vector
        w = w2
        along = w[0] * n[0] + w[1] * n[1] + w[2] * n[2]
    sx, sy, sz = w[0] - along * n[0], w[1] - along * n[1], w[2] - along * n[2]
    size = math.sqrt(sx * sx + sy * sy + sz * sz)
    s = (sx / size, sy / size, sz / size)
    t = (n[1] * s[2] - n[2] * s[1], n[2] * s[0] - n[0] * s[2], n[0] * s[1] - n[1] * s[0])
    return n, s, t, length


@inlined
def hit_code(strands, c, u, nx, ny, nz, time):
    """The angle (radians) of the normal (nx, ny, nz) (any length) around the tangent of segment ``c`` at ``u``,
    ray time ``time``."""
    _, _, du, _ = curve_at(strands, c, u, time)
    _, s, t, _ = _frame(strands, c, du, time)
    return math.atan2(nx * t[0] + ny * t[1] + nz * t[2], nx * s[0] + ny * s[1] + nz * s[2])


@kernel
def curve_surface(strands, c, u, angle, time):
    """(point, unit outward normal, the same as shading normal) of segment ``c`` where the hit code (u, ``angle``)
    points: the point is the curve's centre at ``u`` plus its radius across the tangent at ``angle`` around it;
    the normal is the tube's own, which leans along the tangent where the radius changes (by -r'/|C'|, as
    Embree's Ng): rays leave the surface along it, so a tapering strand does not catch the rays it sheds,
    and the shading normal is the same (as Cycles' N and Ng of a thick curve are), so no bounce lies on
    different sides of the two. ``time``: the ray's."""
    centre, r, du, dr = curve_at(strands, c, u, time)
    axis, s, t, length = _frame(strands, c, du, time)
    ca, sa = math.cos(angle), math.sin(angle)
    lean = min(max(-dr / length, -0.99), 0.99) if length > 0.0 else 0.0
    across = math.sqrt(1.0 - lean * lean)
    n = (across * (ca * s[0] + sa * t[0]) + lean * axis[0], across * (ca * s[1] + sa * t[1]) + lean * axis[1],
         across * (ca * s[2] + sa * t[2]) + lean * axis[2])
    return (centre[0] + r * (ca * s[0] + sa * t[0]), centre[1] + r * (ca * s[1] + sa * t[1]),
            centre[2] + r * (ca * s[2] + sa * t[2])), n, n


@inlined
def curve_tangent(strands, c, u, time):
    """d centre / du of segment ``c`` at ``u``, ray time ``time`` (Cycles' dPdu of a curve; not unit)."""
    return curve_at(strands, c, u, time)[2]


EXIT_MARGIN = 1e-3  # a ray crossing a strand starts this fraction of the radius outside its far wall
EXIT_STEPS = 3  # Newton steps that find the curve parameter of the far wall's point


@kernel
def _radial(strands, c, u, x, time):
    """(centre, radius, unit tangent, |C'|, the part of x - centre across the tangent) at ``u``."""
    centre, r, du, _ = curve_at(strands, c, u, time)
    size = math.sqrt(du[0] * du[0] + du[1] * du[1] + du[2] * du[2])
    a = (du[0] / size, du[1] / size, du[2] / size) if size > 0.0 else (0.0, 0.0, 1.0)
    ex, ey, ez = x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]
    along = ex * a[0] + ey * a[1] + ez * a[2]
    return centre, r, a, size, (ex - along * a[0], ey - along * a[1], ez - along * a[2]), along


@kernel
def leave_tube(strands, c, u, p, d, time):
    """(origin, distance travelled) of a ray from ``p`` (on segment ``c``'s surface at ``u``) along unit ``d`` that
    points into the tube: it starts just outside the tube's far wall; distance 0 where ``d`` points outward.
    A fibre's closure scatters light through the fibre as if it left where it entered (a far-field model): the
    path goes on from the far side, as Cycles' rays skip the primitive they leave (its self-intersection test),
    instead of meeting the tube's inside. The far wall: the chord of the circle the ray's projection crosses
    (exact for a straight tube of one radius), then the curve's point nearest it (Newton on (x - C(u)) . C'(u) =
    0, the segment's u clamped to 0-1), and the origin put radially ``EXIT_MARGIN`` outside the radius there (a
    bent or tapering strand's wall is not where the straight chord ends). ``time``: the ray's."""
    centre, r, a, size, e, _ = _radial(strands, c, u, p, time)
    e_size = math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
    if not (size > 0.0 and r > 0.0 and e_size > 0.0):
        return p, 0.0
    inward = -(d[0] * e[0] + d[1] * e[1] + d[2] * e[2]) / e_size
    if inward <= 0.0:
        return p, 0.0
    d_along = d[0] * a[0] + d[1] * a[1] + d[2] * a[2]
    t = 2.0 * r * inward / max(1.0 - d_along * d_along, 1e-6)  # the chord of the circle of radius r
    x = (p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2])
    w = min(max(u + t * d_along / size, 0.0), 1.0)
    for _ in range(EXIT_STEPS):
        centre, r, a, size, e, along = _radial(strands, c, w, x, time)
        if not size > 0.0:
            break
        w = min(max(w + along / size, 0.0), 1.0)
    centre, r, a, size, e, along = _radial(strands, c, w, x, time)
    e_size = math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
    if not e_size > 0.0:
        return x, t
    reach = r * (1.0 + EXIT_MARGIN) / e_size
    q = (centre[0] + along * a[0] + reach * e[0], centre[1] + along * a[1] + reach * e[1],
         centre[2] + along * a[2] + reach * e[2])
    return q, math.sqrt((q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2 + (q[2] - p[2]) ** 2)
