"""A point seen by the camera: which pixel it lands on and the camera's importance there, for light
paths that connect to the camera (pinhole and thin lens; ``stages.camera`` defines both).

A pixel's value is the mean radiance over its raster area (box) or under the truncated Gaussian the
camera stage samples, and over the lens. For a lens point l and a camera-space ray from l that
leaves the optical axis at angle θ, a raster area dA maps to the solid angle

    dω = cos³θ · (tan_w tan_h / (W H)) · dA

(the film plane at distance 1, or the focus plane at distance f seen from l: both give cos³θ). So a
radiance L arriving at l from a surface point y adds to its pixel

    L · |cos_y| / d² · W H / (tan_w tan_h cos³θ) · filter weight

per unit area at y — Veach's importance of a pinhole, spread over the lens by the lens point drawn
with the density the camera stage uses. With the Gaussian filter a point spreads over several
pixels; one is drawn ∝ its filter weight, which keeps one splat per light path.
"""

from __future__ import annotations

import math

from ..jit import inlined
from .camera import FILTER_BOX, THIN_LENS, aperture_point
from .camera_motion import camera_pose, quaternion_rotate


@inlined
def filter_weight(camera, offset):
    """Density of the pixel filter (per raster unit) at ``offset`` from a pixel's centre, one axis."""
    if camera.filter_kind == FILTER_BOX:
        return 1.0 if -0.5 <= offset < 0.5 else 0.0
    width = camera.filter_width_px
    if abs(offset) > width:
        return 0.0
    sigma = width / 3.0
    z = offset / sigma
    return math.exp(-0.5 * z * z) / (sigma * math.sqrt(2.0 * math.pi) * (1.0 - 2.0 * camera.filter_cdf_lo))


@inlined
def filter_pick(camera, x, count, u):
    """(pixel index along one axis or -1, total filter weight) for raster coordinate ``x`` on an axis of
    ``count`` pixels: a pixel drawn ∝ its filter weight, so the weight of the pick is the total."""
    if camera.filter_kind == FILTER_BOX:
        index = int(math.floor(x))
        if 0 <= index < count:
            return index, 1.0
        return -1, 0.0
    width = camera.filter_width_px
    lo = max(0, int(math.ceil(x - 0.5 - width)))
    hi = min(count - 1, int(math.floor(x - 0.5 + width)))
    total = 0.0
    for i in range(lo, hi + 1):
        total += filter_weight(camera, x - (i + 0.5))
    if not total > 0.0:
        return -1, 0.0
    target = u * total
    below = 0.0
    for i in range(lo, hi + 1):
        below += filter_weight(camera, x - (i + 0.5))
        if target < below:
            return i, total
    return hi, total


@inlined
def _lens_and_view(camera, p, lx, ly, time):
    """(lens point (the render's space), w = ``p`` - lens point, w in the camera's frame) of lens position (lx, ly),
    the camera where it stands at ray time ``time`` (``camera_motion.camera_pose`` for a moving one)."""
    if camera.poses.shape[0] > 0:
        c, q = camera_pose(camera.poses, time)
        offset = quaternion_rotate(q, (lx, ly, 0.0))
        lens = (c[0] + offset[0], c[1] + offset[1], c[2] + offset[2])
        w = (p[0] - lens[0], p[1] - lens[1], p[2] - lens[2])
        return lens, w, quaternion_rotate((q[0], -q[1], -q[2], -q[3]), w)  # the inverse rotation
    r = camera.rotation
    c = camera.origin
    lens = (c[0] + r[0, 0] * lx + r[0, 1] * ly, c[1] + r[1, 0] * lx + r[1, 1] * ly, c[2] + r[2, 0] * lx + r[2, 1] * ly)
    w = (p[0] - lens[0], p[1] - lens[1], p[2] - lens[2])
    return lens, w, (r[0, 0] * w[0] + r[1, 0] * w[1] + r[2, 0] * w[2], r[0, 1] * w[0] + r[1, 1] * w[1]
                     + r[2, 1] * w[2], r[0, 2] * w[0] + r[1, 2] * w[1] + r[2, 2] * w[2])


@inlined
def connect_to_camera(camera, p, u_lens, u_filter, time):
    """(pixel or -1, lens point (the render's space), importance W, distance d (m)) of the surface
    point ``p``: radiance L leaving ``p`` toward the lens point adds L |cos_p| / d² · W per unit area at
    ``p`` to the pixel (filter weight included). ``u_lens``, ``u_filter``: pairs of uniforms; ``time``: the
    path's ray time (a moving camera's pose then)."""
    lx = ly = 0.0
    if camera.kind == THIN_LENS:
        lx, ly = aperture_point(camera, u_lens[0], u_lens[1])
    lens, w, (vx, vy, vz) = _lens_and_view(camera, p, lx, ly, time)
    dist = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    if not (vz < 0.0 and dist > 0.0):
        return -1, lens, 0.0, dist
    if camera.kind == THIN_LENS:
        f = camera.focus_distance_m
        fx = (lx + vx * f / -vz) / f
        fy = (ly + vy * f / -vz) / f
    else:
        fx, fy = vx / -vz, vy / -vz
    x = ((fx - camera.shift_x) / camera.tan_w + 0.5) * camera.width
    y = (0.5 - (fy - camera.shift_y) / camera.tan_h) * camera.height
    if not (math.isfinite(x) and math.isfinite(y)):
        return -1, lens, 0.0, dist
    column, wx = filter_pick(camera, x, camera.width, u_filter[0])
    row, wy = filter_pick(camera, y, camera.height, u_filter[1])
    if column < 0 or row < 0:
        return -1, lens, 0.0, dist
    cos_theta = -vz / dist
    importance = camera.width * camera.height / (camera.tan_w * camera.tan_h * cos_theta * cos_theta * cos_theta)
    return row * camera.width + column, lens, importance * wx * wy, dist
