"""Stage 1: new paths. Pixel and sample numbers, wavelengths, and the camera ray of each path.

Paths ``first .. first + count`` of a pass cover ``pixels`` with ``samples_per_pixel`` consecutive
paths each; path p is sample ``first_sample + p % spp`` of pixel ``pixels[p // spp]``. Raster positions
come from the sampler's pixel slot: uniform in the pixel ("box"), or filter importance sampling of a
Gaussian of standard deviation width/3 truncated at ``width`` ("gaussian", weight 1).

Cameras (``CameraData``, in the render's space: world positions minus the render's origin, where the
camera sits at ``origin``: 0 for a final render, anywhere near it in the viewport): ``PINHOLE``, ``THIN_LENS``
(aperture radius focal/(2 f-stop), sharp at ``focus_distance_m`` along the view axis). Blender's
conventions: the camera looks down its local -Z, +Y up; lens shift in units of the larger film side.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined, kernel
from ..sampler import SLOT_HERO, SLOT_LENS, SLOT_PIXEL, SLOT_WAVELENGTH, pixel_seed, sample_1d, sample_2d
from ..spectra.wavelength_sampling import MODE_GAUSSIAN_RGB, inverse_normal_cdf, sample_wavelengths
from ..state import PREV_DELTA
from ..warps import concentric_disk
from .queue import push_ray

PINHOLE = 0
THIN_LENS = 1
FILTER_BOX = 0
FILTER_GAUSSIAN = 1

#: kind, rotation float64 [3, 3] (camera to world), tan_w / tan_h (film size / focal length), shift_x /
#: shift_y (in the same units), aperture_radius_m, focus_distance_m, width, height (pixels),
#: filter_kind, filter_width_px, filter_cdf_lo (Gaussian mass below -width), origin float64 [3] (the
#: camera's position in the render's space, m).
CameraData = namedtuple(
    "CameraData",
    "kind rotation tan_w tan_h shift_x shift_y aperture_radius_m focus_distance_m width height "
    "filter_kind filter_width_px filter_cdf_lo origin",
)


def camera_data(camera, settings, kind, origin_m=(0.0, 0.0, 0.0)) -> CameraData:
    """``CameraData`` of a ``scene.Camera`` for ``kind`` (``PINHOLE`` or ``THIN_LENS``), the camera at
    ``origin_m`` in the render's space."""
    from scipy.special import ndtr

    width, height = (int(r) for r in camera.resolution)
    f = float(camera.focal_length_mm)
    larger = max(camera.film_width_mm, camera.film_height_mm) / f
    aperture = camera.focal_length_mm / (2.0 * camera.fstop) / 1000.0 if kind == THIN_LENS else 0.0
    sigma = settings.filter_width_px / 3.0
    return CameraData(kind, np.ascontiguousarray(np.asarray(camera.camera_to_world, np.float64)[:3, :3]),
                      camera.film_width_mm / f, camera.film_height_mm / f, camera.shift_x * larger,
                      camera.shift_y * larger, aperture, float(camera.focus_distance_m), width, height,
                      FILTER_GAUSSIAN if settings.pixel_filter == "gaussian" else FILTER_BOX,
                      float(settings.filter_width_px), float(ndtr(-settings.filter_width_px / sigma)),
                      np.ascontiguousarray(origin_m, dtype=np.float64))


@inlined
def filter_offset(camera, u):
    """Position in the pixel (0..1 for the box; may leave the pixel for the Gaussian) from a uniform."""
    if camera.filter_kind == FILTER_BOX:
        return u
    sigma = camera.filter_width_px / 3.0
    p = camera.filter_cdf_lo + u * (1.0 - 2.0 * camera.filter_cdf_lo)
    p = min(max(p, 1e-12), 1.0 - 1e-12)
    return 0.5 + sigma * inverse_normal_cdf(p)


@inlined
def film_direction(camera, x, y):
    """Camera-space direction (not unit) with z = -1 through raster position (x, y) (pixels, y down)."""
    return ((x / camera.width - 0.5) * camera.tan_w + camera.shift_x,
            (0.5 - y / camera.height) * camera.tan_h + camera.shift_y, -1.0)


@inlined
def start_path(state, i, pixel, sample, seed):
    """Reset path ``i`` as sample ``sample`` of ``pixel``; returns the pixel's sampler seed."""
    ps = pixel_seed(pixel, seed)
    state.pixel[i] = pixel
    state.sample[i] = sample
    state.seed[i] = ps
    state.flags[i] = PREV_DELTA
    state.eta_scale[i] = 1.0
    state.prev_pdf[i] = 0.0
    state.throughput[i, :] = 1.0
    state.radiance[i, :] = 0.0
    return ps


@inlined
def draw_wavelengths(state, i, ws, sampler, ps, sample):
    u0 = sample_1d(sampler, ps, sample, SLOT_WAVELENGTH)
    u1 = u2 = 0.0
    if ws.mode == MODE_GAUSSIAN_RGB:
        u1 = sample_1d(sampler, ps, sample, SLOT_WAVELENGTH + 1)
        u2 = sample_1d(sampler, ps, sample, SLOT_WAVELENGTH + 2)
    sample_wavelengths(ws, u0, u1, u2, state.wavelength[i], state.wavelength_pdf[i])
    k = state.wavelength.shape[1]
    state.hero[i] = min(int(sample_1d(sampler, ps, sample, SLOT_HERO) * k), k - 1)


@inlined
def camera_ray(camera, x, y, lens_u, lens_v):
    """(origin, unit direction) of the camera ray through raster position (x, y) (pixels from the
    top-left corner) and lens sample (lens_u, lens_v), in the render's space."""
    d = film_direction(camera, x, y)
    o = (0.0, 0.0, 0.0)
    if camera.kind == THIN_LENS:
        lx, ly = concentric_disk(lens_u, lens_v)
        lx *= camera.aperture_radius_m
        ly *= camera.aperture_radius_m
        f = camera.focus_distance_m
        o = (lx, ly, 0.0)
        d = (d[0] * f - lx, d[1] * f - ly, -f)
    r = camera.rotation
    c = camera.origin
    wo = (c[0] + r[0, 0] * o[0] + r[0, 1] * o[1] + r[0, 2] * o[2],
          c[1] + r[1, 0] * o[0] + r[1, 1] * o[1] + r[1, 2] * o[2],
          c[2] + r[2, 0] * o[0] + r[2, 1] * o[1] + r[2, 2] * o[2])
    wd = (r[0, 0] * d[0] + r[0, 1] * d[1] + r[0, 2] * d[2],
          r[1, 0] * d[0] + r[1, 1] * d[1] + r[1, 2] * d[2],
          r[2, 0] * d[0] + r[2, 1] * d[1] + r[2, 2] * d[2])
    n = math.sqrt(wd[0] * wd[0] + wd[1] * wd[1] + wd[2] * wd[2])
    return wo, (wd[0] / n, wd[1] / n, wd[2] / n)


@kernel
def camera_kernel(state, rays, camera, ws, settings, pixels, first, count, samples_per_pixel, first_sample):
    """Start paths ``first .. first + count`` of the pass into rows 0 .. count-1 and queue their rays.
    Returns the number of rays queued (paths with a non-finite ray add nothing)."""
    queued = 0
    for i in range(count):
        p = first + i
        pixel = pixels[p // samples_per_pixel]
        sample = first_sample + p % samples_per_pixel
        ps = start_path(state, i, pixel, sample, settings.seed)
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        ux, uy = sample_2d(settings.sampler, ps, sample, SLOT_PIXEL)
        lu, lv = sample_2d(settings.sampler, ps, sample, SLOT_LENS)
        x = pixel % camera.width + filter_offset(camera, ux)
        y = pixel // camera.width + filter_offset(camera, uy)
        origin, direction = camera_ray(camera, x, y, lu, lv)
        for c in range(3):
            state.mis_origin[i, c] = origin[c]
        queued += push_ray(state, rays, queued, i, origin, direction)
    return queued
