"""The surface points a bake shades, and the rays that find them (numpy; no bpy).

Blender hands a render engine each texel of a bake as a loop triangle of the baked object's evaluated
mesh (``primitive``, -1 where the texel maps to no surface) and barycentric coordinates (u, v) in
Blender's convention: the point is u·c0 + v·c1 + (1 − u − v)·c2 for the triangle's corners c0, c1, c2
in loop-triangle order (Cycles turns them into its own convention in ``init_from_bake``). Prism starts a
ray a small distance off the surface along the shading normal, pointing back at the point, so the
bounce loop's first hit is the baked point and it is seen from along its normal, as Cycles shades it.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

#: How far off the surface a bake ray starts, relative to the point's distance from the render's origin
#: (at least 1 m): far above float32 rounding of the geometry (~1e-7 relative), close enough that no
#: other surface fits in between in practice (Cycles nudges points by the same 1e-4 relative).
START_OFFSET = 1e-4
#: Below this cosine between the shading and the geometric normal, the ray comes along the geometric
#: normal: a shading normal turned that far (bad custom normals) could start the ray behind the surface.
MIN_NORMAL_COSINE = 1e-3
#: Cycles' turn of a camera-view direction (View From ▸ Active Camera): at least this cosine above the shading
#: normal, so faces turned away from the camera still show their shading; and above the face by this much.
SURFACE_NORMAL_OFFSET = 0.2
TRUE_NORMAL_EPSILON = 1e-5


class BakeTriangles(NamedTuple):
    """A baked object's loop triangles in world space: ``corners`` float64 [T, 3, 3] (m), ``corner_normals``
    float64 [T, 3, 3] (unit shading normals; a flat face's are its face normal) and ``mirrored`` (the
    object's transform mirrors it, turning the corners' winding against the normals)."""

    corners: np.ndarray
    corner_normals: np.ndarray
    mirrored: bool = False


class SurfacePoints(NamedTuple):
    """Points of the texels that have one: ``position`` [n, 3] (world, m), ``normal`` [n, 3] (the
    interpolated shading normal, unit), ``geometric`` [n, 3] (the face normal, unit)."""

    position: np.ndarray
    normal: np.ndarray
    geometric: np.ndarray


def _unit(v: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, length, out=np.zeros_like(v), where=length > 0.0)


def surface_points(triangles: BakeTriangles, primitive: np.ndarray, u: np.ndarray, v: np.ndarray) -> SurfacePoints:
    """The points of texels on loop triangles ``primitive`` (int, all valid) at Blender's barycentric
    (``u``, ``v``)."""
    corners = triangles.corners[primitive]
    normals = triangles.corner_normals[primitive]
    w = np.stack([u, v, 1.0 - u - v], axis=-1)[..., None]  # weights of c0, c1, c2
    position = (corners * w).sum(axis=1)
    geometric = _unit(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]))
    if triangles.mirrored:
        geometric = -geometric
    normal = _unit((normals * w).sum(axis=1))
    return SurfacePoints(position, normal, geometric)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", a, b)


def towards_camera(points: SurfacePoints, camera_position, camera_axis=None) -> np.ndarray:
    """Unit directions from ``points`` towards the camera (Bake ▸ View From ▸ Active Camera), turned as
    Cycles turns them so every point is seen from in front: at least ``SURFACE_NORMAL_OFFSET`` above the
    shading normal, towards the normal on the back side, and never behind the face. ``camera_axis``: an
    orthographic camera's +Z axis (its rays are parallel), else None (from ``camera_position``, m)."""
    n, ng = points.normal, points.geometric
    if camera_axis is not None:
        d = np.broadcast_to(np.asarray(camera_axis, np.float64), n.shape).copy()
    else:
        d = _unit(np.asarray(camera_position, np.float64) - points.position)
    dn = _dot(d, n)
    low = dn <= SURFACE_NORMAL_OFFSET
    d[low] = _unit(d[low] - n[low] * (dn[low] - SURFACE_NORMAL_OFFSET)[:, None])
    back = dn <= 0.0
    d[back] = _unit(d[back] + (n[back] - d[back]) * -dn[back][:, None])
    dg = _dot(d, ng)
    behind = dg <= TRUE_NORMAL_EPSILON
    d[behind] = _unit(d[behind] - ng[behind] * (dg[behind] - TRUE_NORMAL_EPSILON)[:, None])
    return d


def bake_ray_table(points: SurfacePoints, render_origin: np.ndarray,
                   seen_from: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(origin, direction) float64 [n, 3] of the rays that find ``points``, origins in the render's space
    (world minus ``render_origin``): each starts ``START_OFFSET`` (relative) off its point along the unit
    direction ``seen_from`` [n, 3] (default: the shading normal) and points straight back, so it meets the
    surface at the point itself, seen from that direction."""
    relative = points.position - np.asarray(render_origin, np.float64)
    along = seen_from
    if along is None:
        along = np.where((_dot(points.normal, points.geometric) > MIN_NORMAL_COSINE)[:, None], points.normal,
                         points.geometric)
    offset = START_OFFSET * np.maximum(1.0, np.abs(relative).max(axis=1, initial=0.0))
    return relative + offset[:, None] * along, -along
