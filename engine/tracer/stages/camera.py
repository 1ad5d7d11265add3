"""Stage 1: new paths. Pixel and sample numbers, wavelengths, and the camera ray of each path.

Paths ``first .. first + count`` of a pass cover ``pixels`` with ``samples_per_pixel`` consecutive
paths each; path p is sample ``first_sample + p % spp`` of pixel ``pixels[p // spp]``. Raster positions
come from the sampler's pixel slot: uniform in the pixel ("box"), or filter importance sampling of a
Gaussian of standard deviation width/3 truncated at ``width`` ("gaussian", weight 1).

Cameras (``CameraData``, in the render's space: world positions minus the render's origin, where the
camera sits at ``origin``: 0 for a final render, anywhere near it in the viewport): a projection
(``projection``: Blender's perspective and orthographic cameras, Cycles' equirectangular and fisheye
panoramas, see ``panorama``) and an aperture (``kind``: ``PINHOLE`` or ``THIN_LENS``, radius focal/(2
f-stop) (1/(2 f-stop) m orthographic, as Cycles), sharp at ``focus_distance_m`` along the view axis —
along the ray for panoramas —, a disc or a regular polygon of ``blades`` corners turned by
``blade_rotation``, squeezed horizontally by 1/``aperture_ratio``). Blender's conventions: the camera
looks down its local -Z, +Y up; lens shift in units of the larger film side (of the orthographic extent).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined, kernel
from ..materials.light_path import start_camera_ray
from ..sampler import SLOT_HERO, SLOT_LENS, SLOT_PIXEL, SLOT_TIME, SLOT_WAVELENGTH, pixel_seed, sample_1d, sample_2d
from ..spectra.wavelength_sampling import MODE_GAUSSIAN_RGB, inverse_normal_cdf, sample_wavelengths
from ..state import CAMERA_PATH, PREV_DELTA
from ..vec3 import tangents
from ..warps import concentric_disk, regular_polygon
from .bounces import start_counts
from .camera_motion import camera_pose, quaternion_rotate, shutter_time
from .panorama import EQUIRECTANGULAR, FISHEYE_EQUIDISTANT, FISHEYE_EQUISOLID, panorama_direction
from .queue import push_ray

PINHOLE = 0
THIN_LENS = 1
FILTER_BOX = 0
FILTER_GAUSSIAN = 1
PERSPECTIVE = 0
ORTHOGRAPHIC = 1
PROJECTIONS = {"perspective": PERSPECTIVE, "orthographic": ORTHOGRAPHIC, "equirectangular": EQUIRECTANGULAR,
               "fisheye_equidistant": FISHEYE_EQUIDISTANT, "fisheye_equisolid": FISHEYE_EQUISOLID}

#: kind, projection, rotation float64 [3, 3] (camera to world), tan_w / tan_h (film size / focal length;
#: orthographic: the view's extent in metres), shift_x / shift_y (in the same units), aperture_radius_m,
#: focus_distance_m, blades (0: a disc), blade_rotation (rad), aperture_ratio, panorama float64 [4]
#: (``stages.panorama``), width, height (pixels), filter_kind, filter_width_px, filter_cdf_lo (Gaussian
#: mass below -width), origin float64 [3] (the camera's position in the render's space, m), ortho_start_m
#: (where orthographic rays start on the camera's +Z axis, m: Clip Start in front of the camera for a
#: render), clip_start_m / clip_end_m (Blender's Clip Start / Clip End, m: camera rays see geometry between
#: these depths along the view axis, along the ray for panoramas, as Cycles; orthographic rays start at
#: Clip Start through ``ortho_start_m``, so their ``clip_start_m`` is 0; ``camera_clip`` applies Clip End),
#: shutter_times float64 [M] (motion blur: the ray time's inverse CDF, ``motion.shutter_times``; empty: no
#: motion blur, every path at time 0.5), poses float64 [S, 7] (a moving camera: position in the render's
#: space and rotation quaternion w, x, y, z at the shutter's S steps, ``motion.camera_poses``; empty: the
#: camera stands at ``origin`` with ``rotation``).
CameraData = namedtuple(
    "CameraData",
    "kind projection rotation tan_w tan_h shift_x shift_y aperture_radius_m focus_distance_m blades blade_rotation "
    "aperture_ratio panorama width height filter_kind filter_width_px filter_cdf_lo origin ortho_start_m "
    "clip_start_m clip_end_m shutter_times poses",
)


def camera_data(camera, settings, kind, origin_m=(0.0, 0.0, 0.0)) -> CameraData:
    """``CameraData`` of a ``scene.Camera`` for ``kind`` (``PINHOLE`` or ``THIN_LENS``), the camera at
    ``origin_m`` in the render's space."""
    from scipy.special import ndtr

    from .panorama import panorama_parameters

    from ..motion import camera_poses

    width, height = (int(r) for r in camera.resolution)
    projection = PROJECTIONS[camera.projection]
    shutter = np.zeros(0) if camera.shutter_times is None else np.asarray(camera.shutter_times, np.float64)
    poses = np.zeros((0, 7))
    if len(shutter) and camera.motion_to_world is not None:
        # the render's space is the world less (camera position - origin_m)
        world_origin = np.asarray(camera.camera_to_world, np.float64)[:3, 3] - np.asarray(origin_m, np.float64)
        poses = camera_poses(camera.motion_to_world, world_origin)
    if projection == ORTHOGRAPHIC:
        scale_w, scale_h = float(camera.ortho_width_m), float(camera.ortho_height_m)
        aperture = 1.0 / (2.0 * camera.fstop) if kind == THIN_LENS else 0.0
    else:
        f = float(camera.focal_length_mm)
        scale_w, scale_h = camera.film_width_mm / f, camera.film_height_mm / f
        aperture = camera.focal_length_mm / (2.0 * camera.fstop) / 1000.0 if kind == THIN_LENS else 0.0
    larger = max(scale_w, scale_h)
    blades = int(camera.aperture_blades) if camera.aperture_blades >= 3 else 0
    sigma = settings.filter_width_px / 3.0
    return CameraData(kind, projection, np.ascontiguousarray(np.asarray(camera.camera_to_world, np.float64)[:3, :3]),
                      scale_w, scale_h, camera.shift_x * larger, camera.shift_y * larger, aperture,
                      float(camera.focus_distance_m), blades, float(camera.aperture_rotation_rad),
                      float(camera.aperture_ratio), panorama_parameters(camera), width, height,
                      FILTER_GAUSSIAN if settings.pixel_filter == "gaussian" else FILTER_BOX,
                      float(settings.filter_width_px), float(ndtr(-settings.filter_width_px / sigma)),
                      np.ascontiguousarray(origin_m, dtype=np.float64),
                      float(camera.ortho_start_m - camera.clip_start_m) if projection == ORTHOGRAPHIC else 0.0,
                      0.0 if projection == ORTHOGRAPHIC else float(camera.clip_start_m), float(camera.clip_end_m),
                      np.ascontiguousarray(shutter), poses)


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
def start_path(state, i, pixel, sample, seed, medium):
    """Reset path ``i`` as sample ``sample`` of ``pixel``, in ``medium`` (``KernelSettings.camera_medium``);
    returns the pixel's sampler seed."""
    ps = pixel_seed(pixel, seed)
    state.pixel[i] = pixel
    state.sample[i] = sample
    state.seed[i] = ps
    state.flags[i] = PREV_DELTA | CAMERA_PATH
    state.medium[i] = medium
    state.transparency[i] = 0.0
    state.eta_scale[i] = 1.0
    state.prev_pdf[i] = 0.0
    state.min_pdf[i] = math.inf  # no bounce yet: Filter Glossy leaves the first surface alone
    state.throughput[i, :] = 1.0
    state.radiance[i, :] = 0.0
    state.time[i] = 0.5
    state.receiver[i] = -1  # camera rays see every emitter (``light_linking``)
    start_camera_ray(state, i)
    start_counts(state, i)
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


@kernel
def aperture_point(camera, u, v):
    """A point of the aperture (camera-space metres in its plane): uniform over the disc or polygon."""
    if camera.blades >= 3:
        x, y = regular_polygon(u, v, camera.blades, camera.blade_rotation)
    else:
        x, y = concentric_disk(u, v)
    return x * camera.aperture_radius_m / camera.aperture_ratio, y * camera.aperture_radius_m


@inlined
def camera_space_ray(camera, x, y, lens_u, lens_v):
    """(origin, direction (not unit; zero: no ray)) in camera space (-Z forward) through raster
    position (x, y) and lens sample (lens_u, lens_v)."""
    if camera.projection == PERSPECTIVE:
        d = film_direction(camera, x, y)
        o = (0.0, 0.0, 0.0)
        if camera.kind == THIN_LENS:
            lx, ly = aperture_point(camera, lens_u, lens_v)
            f = camera.focus_distance_m
            o = (lx, ly, 0.0)
            d = (d[0] * f - lx, d[1] * f - ly, -f)
        return o, d
    if camera.projection == ORTHOGRAPHIC:
        p = film_direction(camera, x, y)
        start = camera.ortho_start_m
        o = (p[0], p[1], start)
        d = (0.0, 0.0, -1.0)
        if camera.kind == THIN_LENS:
            lx, ly = aperture_point(camera, lens_u, lens_v)
            o = (p[0] + lx, p[1] + ly, start)
            d = (-lx, -ly, -(camera.focus_distance_m + start))
        return o, d
    d = panorama_direction(camera, x / camera.width, 1.0 - y / camera.height)
    o = (0.0, 0.0, 0.0)
    if camera.kind == THIN_LENS and (d[0] != 0.0 or d[1] != 0.0 or d[2] != 0.0):
        lx, ly = aperture_point(camera, lens_u, lens_v)
        s, t = tangents(d)
        f = camera.focus_distance_m
        o = (lx * s[0] + ly * t[0], lx * s[1] + ly * t[1], lx * s[2] + ly * t[2])
        d = (d[0] * f - o[0], d[1] * f - o[1], d[2] * f - o[2])
    return o, d


@inlined
def near_clip_distance(camera, x, y):
    """How far (m) along the unit camera ray through raster position (x, y) it starts: Clip Start on the
    view axis (perspective: Clip Start over the cosine of the pinhole ray through (x, y), as Cycles, also
    with depth of field), along the ray for panoramas, 0 for orthographic cameras (``ortho_start_m``)."""
    if camera.clip_start_m <= 0.0:
        return 0.0
    if camera.projection == PERSPECTIVE:
        f = film_direction(camera, x, y)
        return camera.clip_start_m * math.sqrt(f[0] * f[0] + f[1] * f[1] + 1.0)
    return camera.clip_start_m


@inlined
def camera_ray(camera, x, y, lens_u, lens_v, time):
    """(origin, unit direction) of the camera ray through raster position (x, y) (pixels from the
    top-left corner) and lens sample (lens_u, lens_v) at ray time ``time`` (a moving camera's pose then),
    in the render's space, starting at Clip Start; the direction is (0, 0, 0) where the camera sees
    nothing (outside a fisheye's circle)."""
    o, d = camera_space_ray(camera, x, y, lens_u, lens_v)
    if d[0] == 0.0 and d[1] == 0.0 and d[2] == 0.0:
        return o, d
    if camera.poses.shape[0] > 0:
        c, q = camera_pose(camera.poses, time)
        wo = quaternion_rotate(q, o)
        wo = (c[0] + wo[0], c[1] + wo[1], c[2] + wo[2])
        wd = quaternion_rotate(q, d)
    else:
        r = camera.rotation
        c = camera.origin
        wo = (c[0] + r[0, 0] * o[0] + r[0, 1] * o[1] + r[0, 2] * o[2],
              c[1] + r[1, 0] * o[0] + r[1, 1] * o[1] + r[1, 2] * o[2],
              c[2] + r[2, 0] * o[0] + r[2, 1] * o[1] + r[2, 2] * o[2])
        wd = (r[0, 0] * d[0] + r[0, 1] * d[1] + r[0, 2] * d[2],
              r[1, 0] * d[0] + r[1, 1] * d[1] + r[1, 2] * d[2],
              r[2, 0] * d[0] + r[2, 1] * d[1] + r[2, 2] * d[2])
    n = math.sqrt(wd[0] * wd[0] + wd[1] * wd[1] + wd[2] * wd[2])
    unit = (wd[0] / n, wd[1] / n, wd[2] / n)
    near = near_clip_distance(camera, x, y)
    return (wo[0] + near * unit[0], wo[1] + near * unit[1], wo[2] + near * unit[2]), unit


@kernel
def camera_kernel(state, rays, camera, ws, settings, pixels, first, count, samples_per_pixel, first_sample):
    """Start paths ``first .. first + count`` of the pass into rows 0 .. count-1 and queue their rays.
    Returns the number of rays queued (paths with a non-finite ray add nothing)."""
    queued = 0
    for i in range(count):
        p = first + i
        pixel = pixels[p // samples_per_pixel]
        sample = first_sample + p % samples_per_pixel
        ps = start_path(state, i, pixel, sample, settings.seed, settings.camera_medium)
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        ux, uy = sample_2d(settings.sampler, ps, sample, SLOT_PIXEL)
        lu, lv = sample_2d(settings.sampler, ps, sample, SLOT_LENS)
        x = pixel % camera.width + filter_offset(camera, ux)
        y = pixel // camera.width + filter_offset(camera, uy)
        if camera.shutter_times.shape[0] > 0:
            state.time[i] = shutter_time(camera.shutter_times, sample_1d(settings.sampler, ps, sample, SLOT_TIME))
        origin, direction = camera_ray(camera, x, y, lu, lv, state.time[i])
        if direction[0] == 0.0 and direction[1] == 0.0 and direction[2] == 0.0:
            continue  # outside a fisheye's circle: the path adds nothing
        for c in range(3):
            state.mis_origin[i, c] = origin[c]
        queued += push_ray(state, rays, queued, i, origin, direction)
    return queued
