"""Stage 1 for a real lens: new paths whose camera rays are traced through the lens elements.

As ``camera`` (pixel, sample, wavelengths, filter), then each path's ray is traced from its film point
through the lens at the path's hero wavelength (``lens.camera_kernel``): the lens disperses, so the
path starts collapsed, its hero column carrying K × the lens weight (vignetting, cos⁴ fall-off; 0 when
the lens blocks the ray, and then the path adds nothing).
"""

from __future__ import annotations

from ..jit import kernel
from ..lens.camera_kernel import camera_ray, film_point_mm
from ..sampler import SLOT_LENS, SLOT_PIXEL, SLOT_TIME, sample_1d, sample_2d
from ..state import COLLAPSED
from .camera import draw_wavelengths, filter_offset, start_path
from .camera_motion import camera_pose, quaternion_rotate, shutter_time
from .queue import push_ray


@kernel
def real_lens_kernel(state, rays, camera, lens, ws, settings, pixels, first, count, samples_per_pixel, first_sample):
    """Start paths ``first .. first + count`` of the pass through the lens ``lens`` (``RealLensTables``);
    ``camera`` (``CameraData``) gives the filter and the camera's rotation and position. Returns the rays queued."""
    queued = 0
    k = state.throughput.shape[1]
    r = camera.rotation
    at = camera.origin
    for i in range(count):
        p = first + i
        pixel = pixels[p // samples_per_pixel]
        sample = first_sample + p % samples_per_pixel
        ps = start_path(state, i, pixel, sample, settings.seed, settings.camera_medium)
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        ux, uy = sample_2d(settings.sampler, ps, sample, SLOT_PIXEL)
        lu, lv = sample_2d(settings.sampler, ps, sample, SLOT_LENS)
        fx, fy = film_point_mm(lens, pixel % camera.width + filter_offset(camera, ux),
                               pixel // camera.width + filter_offset(camera, uy))
        hero = state.hero[i]
        weight, ox, oy, oz, dx, dy, dz = camera_ray(lens, fx, fy, lu, lv, state.wavelength[i, hero])
        for c in range(k):
            state.throughput[i, c] = k * weight if c == hero else 0.0
        state.flags[i] |= COLLAPSED
        if not weight > 0.0:
            continue
        if camera.shutter_times.shape[0] > 0:
            state.time[i] = shutter_time(camera.shutter_times, sample_1d(settings.sampler, ps, sample, SLOT_TIME))
        if camera.poses.shape[0] > 0:  # a moving camera: its pose at the path's time
            c, q = camera_pose(camera.poses, state.time[i])
            origin = quaternion_rotate(q, (ox, oy, oz))
            origin = (c[0] + origin[0], c[1] + origin[1], c[2] + origin[2])
            direction = quaternion_rotate(q, (dx, dy, dz))
        else:
            origin = (at[0] + r[0, 0] * ox + r[0, 1] * oy + r[0, 2] * oz,
                      at[1] + r[1, 0] * ox + r[1, 1] * oy + r[1, 2] * oz,
                      at[2] + r[2, 0] * ox + r[2, 1] * oy + r[2, 2] * oz)
            direction = (r[0, 0] * dx + r[0, 1] * dy + r[0, 2] * dz, r[1, 0] * dx + r[1, 1] * dy + r[1, 2] * dz,
                         r[2, 0] * dx + r[2, 1] * dy + r[2, 2] * dz)
        for c in range(3):
            state.mis_origin[i, c] = origin[c]
        queued += push_ray(state, rays, queued, i, origin, direction)
    return queued
