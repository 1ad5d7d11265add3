"""The real-lens camera ray, compiled: what the render kernels call once per path.

``RealLensTables`` (built once per render by ``RealLensCamera.kernel_tables()``):

- ``lens``: ``tables.LensTables`` of the stopped-down lens system;
- ``pupil``: ``pupil_sampling.PupilTables`` of its exit-pupil bounds for this film;
- ``film_z_mm``: the film plane in lens coordinates (rear vertex + sensor distance);
- ``centre_irradiance``: cos^4 A / z^2 integrated over the pupil seen from the film centre
  (the value a uniform white scene gives there; weights are divided by it);
- ``width_px``, ``height_px``, ``film_width_mm``, ``film_height_mm``, ``shift_x_mm``,
  ``shift_y_mm``: the raster-to-film mapping (``film_point_mm``).

Placement (camera space, metres): the film is at the camera origin and the lens extends
along -Z (the camera looks down -Z, +Y up); lens coordinates map by x, y unchanged and
Z = (z - film_z) / 1000. A lens forms an inverted image, so the film is read rotated by
180 degrees: raster right/up is lens -x/-y.

Weight of a ray drawn toward a point of area-A shape on the rear vertex plane at axial
distance z from the film point: cos^4(theta) A / z^2 (its share of the irradiance from a
uniform-radiance scene) divided by ``centre_irradiance``; so a uniform white scene gives 1
at the film centre at every f-stop, with physical vignetting and cos^4 fall-off.
"""

from __future__ import annotations

import math
from collections import namedtuple

from ..jit import kernel
from .pupil_sampling import sample_exit_pupil
from .ray_fate import FATE_ALIVE
from .trace_kernel import trace_ray

RealLensTables = namedtuple(
    "RealLensTables",
    "lens pupil film_z_mm centre_irradiance width_px height_px film_width_mm film_height_mm shift_x_mm shift_y_mm",
)


@kernel
def film_point_mm(camera, raster_x, raster_y):
    """The film point (lens x, y in mm) of a raster position (pixels, origin at the top left,
    y down), rotated by 180 degrees as the film is read."""
    sensor_x = (raster_x / camera.width_px - 0.5) * camera.film_width_mm + camera.shift_x_mm
    sensor_y = (0.5 - raster_y / camera.height_px) * camera.film_height_mm + camera.shift_y_mm
    return -sensor_x, -sensor_y


@kernel
def camera_ray(camera, film_x_mm, film_y_mm, u0, u1, wavelength_nm):
    """One camera ray through the real lens from a film point.

    ``camera``: ``RealLensTables``; ``film_x_mm``, ``film_y_mm``: the film point in lens
    coordinates (``film_point_mm`` of a raster position); ``u0``, ``u1`` in [0, 1): the lens
    sample; ``wavelength_nm``: the wavelength traced (the hero wavelength).

    Returns ``(weight, ox, oy, oz, dx, dy, dz)``: the ray leaving the front element in camera
    space (origin in metres, unit direction) and its weight (see the module docstring). A
    ray the lens blocks, or from a film point outside the image circle, has weight 0,
    origin 0 and direction (0, 0, -1).
    """
    pupil = camera.pupil
    x_mm, y_mm, area_mm2 = sample_exit_pupil(pupil, film_x_mm, film_y_mm, u0, u1)
    if not area_mm2 > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0
    film_z = camera.film_z_mm
    axial_mm = film_z - pupil.rear_z_mm
    direction = (x_mm - film_x_mm, y_mm - film_y_mm, -axial_mm)
    fate, _, p, d = trace_ray(camera.lens, (film_x_mm, film_y_mm, film_z), direction, wavelength_nm, False, None)
    if fate != FATE_ALIVE:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0
    distance2 = direction[0] * direction[0] + direction[1] * direction[1] + axial_mm * axial_mm
    # cos^4 / z^2 = z^2 / distance^4 with cos = z / distance
    weight = area_mm2 * axial_mm * axial_mm / (distance2 * distance2) / camera.centre_irradiance
    return weight, p[0] * 1e-3, p[1] * 1e-3, (p[2] - film_z) * 1e-3, d[0], d[1], d[2]


@kernel
def camera_rays(camera, film_xy_mm, lens_uv, wavelength_nm, weight, origins_m, directions):
    """``camera_ray`` for each row of ``film_xy_mm`` and ``lens_uv`` [N, 2] at ``wavelength_nm``
    [N], into ``weight`` [N], ``origins_m`` and ``directions`` [N, 3] (camera space)."""
    for k in range(film_xy_mm.shape[0]):
        ray = camera_ray(camera, film_xy_mm[k, 0], film_xy_mm[k, 1], lens_uv[k, 0], lens_uv[k, 1], wavelength_nm[k])
        weight[k] = ray[0]
        origins_m[k, 0], origins_m[k, 1], origins_m[k, 2] = ray[1], ray[2], ray[3]
        directions[k, 0], directions[k, 1], directions[k, 2] = ray[4], ray[5], ray[6]


@kernel
def film_points_mm(camera, raster_xy, film_xy_mm):
    """``film_point_mm`` for each row of ``raster_xy`` [N, 2], into ``film_xy_mm`` [N, 2]."""
    for k in range(raster_xy.shape[0]):
        film_xy_mm[k, 0], film_xy_mm[k, 1] = film_point_mm(camera, raster_xy[k, 0], raster_xy[k, 1])
