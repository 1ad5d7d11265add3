"""Cycles' panoramic projections: camera-space directions of image coordinates (u, v) in [0, 1]²
(u to the right, v up, over the whole image whatever its aspect).

Each projection is defined in Cycles' panorama frame — x forward, y to the left, z up — which is
Blender's camera space (X right, Y up, -Z forward) as (X, Y, Z) = (-y, z, -x):

- ``EQUIRECTANGULAR``: longitude λ = lon_min + u (lon_max - lon_min), latitude β = lat_min +
  v (lat_max - lat_min); direction (cos β cos λ, -cos β sin λ, sin β).
- ``FISHEYE_EQUIDISTANT``: (a, b) = 2 (u, v) - 1 (the circle fills the image, an ellipse on a wide
  one), r = |(a, b)| ≤ 1, θ = r · fov / 2 from the axis.
- ``FISHEYE_EQUISOLID``: (a, b) = ((u - ½) · sensor width, (v - ½) · sensor height) (mm), r ≤
  2 lens sin(fov / 4), θ = 2 asin(r / (2 lens)).

Fisheyes point (cos θ, -(a/r) sin θ, (b/r) sin θ); beyond their circle there is no ray (zero vector).
``CameraData.panorama`` holds [lon_min, lon_max, lat_min, lat_max] or [fov, lens_mm, sensor width mm,
sensor height mm].
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel

EQUIRECTANGULAR = 2
FISHEYE_EQUIDISTANT = 3
FISHEYE_EQUISOLID = 4


def panorama_parameters(camera) -> np.ndarray:
    """``CameraData.panorama`` of a ``scene.Camera``."""
    if camera.projection == "equirectangular":
        return np.array([camera.longitude_min_rad, camera.longitude_max_rad, camera.latitude_min_rad,
                         camera.latitude_max_rad], np.float64)
    return np.array([camera.fisheye_fov_rad, camera.fisheye_lens_mm, camera.film_width_mm, camera.film_height_mm],
                    np.float64)


@kernel
def _fisheye(theta, a, b, r):
    if r > 0.0:
        s = math.sin(theta) / r
        x, y, z = math.cos(theta), -a * s, b * s
    else:
        x, y, z = 1.0, 0.0, 0.0
    return (-y, z, -x)


@kernel
def panorama_direction(camera, u, v):
    """Unit camera-space direction at image coordinates (u, v) (v up), or (0, 0, 0) (no ray)."""
    p = camera.panorama
    if camera.projection == EQUIRECTANGULAR:
        longitude = p[0] + u * (p[1] - p[0])
        latitude = p[2] + v * (p[3] - p[2])
        c = math.cos(latitude)
        x, y, z = c * math.cos(longitude), -c * math.sin(longitude), math.sin(latitude)
        return (-y, z, -x)
    if camera.projection == FISHEYE_EQUIDISTANT:
        a = 2.0 * u - 1.0
        b = 2.0 * v - 1.0
        r = math.sqrt(a * a + b * b)
        if r > 1.0:
            return (0.0, 0.0, 0.0)
        return _fisheye(r * p[0] * 0.5, a, b, r)
    a = (u - 0.5) * p[2]
    b = (v - 0.5) * p[3]
    r = math.sqrt(a * a + b * b)
    if r > 2.0 * p[1] * math.sin(p[0] * 0.25) or r > 2.0 * p[1]:
        return (0.0, 0.0, 0.0)
    return _fisheye(2.0 * math.asin(r / (2.0 * p[1])), a, b, r)
