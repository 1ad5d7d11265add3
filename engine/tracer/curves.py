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
(a radius of 0.1 mm falling to 0 over centimetres) the two differ by about 0.1 degree. Curves do not move with motion blur,
carry no UV map and are not sampled as lights.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .jit import inlined, kernel
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

    def __len__(self) -> int:
        return int(len(self.segments))


def no_curves() -> tuple[np.ndarray, np.ndarray]:
    """(``Geometry.curves``, ``Geometry.curve_segments``) of a render without hair."""
    return np.zeros((0, 4), np.float32), np.zeros(0, np.int32)


def curve_count(curves: CurveSegments | None) -> int:
    """How many segments render (all of them: the export keeps finite strands only)."""
    return 0 if curves is None else len(curves)


def camera_relative(curves: CurveSegments | None, offset) -> tuple[np.ndarray, np.ndarray]:
    """(float32 [P, 4]: control point - ``offset`` (subtracted in float64), radius; int32 [C] segments)."""
    if curves is None or not len(curves):
        return no_curves()
    table = np.empty((len(curves.radii), 4), np.float64)
    table[:, :3] = np.asarray(curves.points, np.float64) - np.asarray(offset, np.float64)
    table[:, 3] = np.asarray(curves.radii, np.float64)
    return np.ascontiguousarray(table.astype(np.float32)), np.ascontiguousarray(curves.segments, np.int32)


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
def curve_at(controls, segments, c, u):
    """(centre (x, y, z), radius, d centre / du, d radius / du) of segment ``c`` at parameter ``u``."""
    k = segments[c]
    w, d = _weights(u)
    x = y = z = r = dx = dy = dz = dr = 0.0
    for i in range(4):
        px, py, pz, pr = float(controls[k + i, 0]), float(controls[k + i, 1]), float(controls[k + i, 2]), \
            float(controls[k + i, 3])
        x += w[i] * px
        y += w[i] * py
        z += w[i] * pz
        r += w[i] * pr
        dx += d[i] * px
        dy += d[i] * py
        dz += d[i] * pz
        dr += d[i] * pr
    return (x, y, z), r, (dx, dy, dz), dr


@inlined
def _frame(controls, segments, c, tangent):
    """(unit tangent, s, t, |tangent|): a right-handed frame around the curve's tangent at a point of segment
    ``c``. s is a vector fixed for the whole segment (across its chord, the control points 2 to 3), made
    perpendicular to the tangent: the frame then turns smoothly along the segment and does not hang on the
    rounding of the tangent (whose components cancel to noise along a straight strand, and round
    differently where the kernels compute it), so a hit's code and its surface agree."""
    k = segments[c]
    cx = float(controls[k + 2, 0]) - float(controls[k + 1, 0])
    cy = float(controls[k + 2, 1]) - float(controls[k + 1, 1])
    cz = float(controls[k + 2, 2]) - float(controls[k + 1, 2])
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
def hit_code(controls, segments, c, u, nx, ny, nz):
    """The angle (radians) of the normal (nx, ny, nz) (any length) around the tangent of segment ``c`` at ``u``."""
    _, _, du, _ = curve_at(controls, segments, c, u)
    _, s, t, _ = _frame(controls, segments, c, du)
    return math.atan2(nx * t[0] + ny * t[1] + nz * t[2], nx * s[0] + ny * s[1] + nz * s[2])


@inlined
def curve_surface(controls, segments, c, u, angle):
    """(point, unit outward normal, the same as shading normal) of segment ``c`` where the hit code (u, ``angle``)
    points: the point is the curve's centre at ``u`` plus its radius across the tangent at ``angle`` around it;
    the normal is the tube's own, which leans along the tangent where the radius changes (by -r'/|C'|, as
    Embree's Ng): rays leave the surface along it, so a tapering strand does not catch the rays it sheds,
    and the shading normal is the same (as Cycles' N and Ng of a thick curve are), so no bounce lies on
    different sides of the two."""
    centre, r, du, dr = curve_at(controls, segments, c, u)
    axis, s, t, length = _frame(controls, segments, c, du)
    ca, sa = math.cos(angle), math.sin(angle)
    lean = min(max(-dr / length, -0.99), 0.99) if length > 0.0 else 0.0
    across = math.sqrt(1.0 - lean * lean)
    n = (across * (ca * s[0] + sa * t[0]) + lean * axis[0], across * (ca * s[1] + sa * t[1]) + lean * axis[1],
         across * (ca * s[2] + sa * t[2]) + lean * axis[2])
    return (centre[0] + r * (ca * s[0] + sa * t[0]), centre[1] + r * (ca * s[1] + sa * t[1]),
            centre[2] + r * (ca * s[2] + sa * t[2])), n, n


@inlined
def curve_tangent(controls, segments, c, u):
    """d centre / du of segment ``c`` at ``u`` (Cycles' dPdu of a curve; not unit)."""
    return curve_at(controls, segments, c, u)[2]
