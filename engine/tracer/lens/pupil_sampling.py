"""Drawing a point on the rear vertex plane toward which a film point sends a camera ray, compiled.

``PupilTables`` are the per-radial-bin shapes ``ExitPupilBounds`` found (lens coordinates, mm):

- ``rear_z_mm``: the plane of the rear surface vertex, where the shapes lie;
- ``bin_width_mm``: radial bin width; a film point at radius r uses bin min(floor(r / w), B - 1);
- ``boxes`` [B, 4]: x0, x1, y0, y1 of each bin's box, for film points on +x (all 0 = nothing passes);
- ``ellipses`` [B, 4]: centre x, centre y, semi-axis x, semi-axis y;
- ``use_ellipse`` [B] bool: sample the ellipse (smaller than the box) instead of the box.

The lens is rotationally symmetric, so a film point at azimuth phi samples its bin's shape
rotated by phi. Sampling is uniform in area over the shape; the area is returned so the
camera can weight by it.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import kernel
from ..warps import concentric_disk

PupilTables = namedtuple("PupilTables", "rear_z_mm bin_width_mm boxes ellipses use_ellipse")


@kernel
def sample_exit_pupil(pupil, film_x_mm, film_y_mm, u0, u1):
    """A point on the rear vertex plane for the film point (``film_x_mm``, ``film_y_mm``), drawn
    uniformly from its bin's shape rotated to the film point's azimuth, from (u0, u1) in [0, 1)^2.

    Returns ``(x_mm, y_mm, area_mm2)``: the point (at z = ``pupil.rear_z_mm``) and the area of
    the shape it was drawn from (0 where no ray from that film radius passes the lens, and
    for a non-finite film point, which has no bin).
    """
    radius_mm = math.sqrt(film_x_mm * film_x_mm + film_y_mm * film_y_mm)
    if not math.isfinite(radius_mm):
        return 0.0, 0.0, 0.0
    # Clamp before converting: a float-to-int conversion of NaN or of a value beyond the int
    # range is undefined, and the optimiser may then read a bin out of bounds.
    last = pupil.boxes.shape[0] - 1
    position = radius_mm / pupil.bin_width_mm
    k = int(position) if position < last else last
    if pupil.use_ellipse[k]:
        e = pupil.ellipses[k]
        disk_x, disk_y = concentric_disk(u0, u1)
        x, y = e[0] + e[2] * disk_x, e[1] + e[3] * disk_y
        area = math.pi * e[2] * e[3]
    else:
        box = pupil.boxes[k]
        x, y = box[0] + u0 * (box[1] - box[0]), box[2] + u1 * (box[3] - box[2])
        area = (box[1] - box[0]) * (box[3] - box[2])
    cos_phi, sin_phi = 1.0, 0.0
    if radius_mm > 0.0:
        cos_phi, sin_phi = film_x_mm / radius_mm, film_y_mm / radius_mm
    return cos_phi * x - sin_phi * y, sin_phi * x + cos_phi * y, area


@kernel
def sample_exit_pupil_rows(pupil, film_xy_mm, uv, points_mm, area_mm2):
    """``sample_exit_pupil`` for each row of ``film_xy_mm`` and ``uv`` [N, 2], into
    ``points_mm`` [N, 3] (on the rear vertex plane) and ``area_mm2`` [N]."""
    for k in range(film_xy_mm.shape[0]):
        x, y, area = sample_exit_pupil(pupil, film_xy_mm[k, 0], film_xy_mm[k, 1], uv[k, 0], uv[k, 1])
        points_mm[k, 0], points_mm[k, 1], points_mm[k, 2] = x, y, pupil.rear_z_mm
        area_mm2[k] = area
