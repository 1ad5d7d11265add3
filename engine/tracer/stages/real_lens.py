"""Camera rays through a real lens (bridge: the lens is traced by ``lens.camera.RealLensCamera``).

Paths are started as in ``camera`` (pixel, sample, wavelengths); the lens is traced at each path's
hero wavelength, so the path starts collapsed: the hero column carries K × the lens weight.
"""

from __future__ import annotations

import numpy as np

from ..jit import kernel
from ..sampler import SLOT_LENS, SLOT_PIXEL, sample_2d
from ..state import COLLAPSED
from .camera import draw_wavelengths, filter_offset, start_path
from .queue import push_ray


@kernel
def begin_lens_paths(state, camera, ws, settings, pixels, first, count, samples_per_pixel, first_sample, xy, uv, hero_nm):
    for i in range(count):
        p = first + i
        pixel = pixels[p // samples_per_pixel]
        sample = first_sample + p % samples_per_pixel
        ps = start_path(state, i, pixel, sample, settings.seed)
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        ux, uy = sample_2d(settings.sampler, ps, sample, SLOT_PIXEL)
        uv[i, 0], uv[i, 1] = sample_2d(settings.sampler, ps, sample, SLOT_LENS)
        xy[i, 0] = pixel % camera.width + filter_offset(camera, ux)
        xy[i, 1] = pixel // camera.width + filter_offset(camera, uy)
        hero_nm[i] = state.wavelength[i, state.hero[i]]


@kernel
def finish_lens_paths(state, rays, count, origin, direction, weight, offset):
    queued = 0
    k = state.throughput.shape[1]
    for i in range(count):
        hero = state.hero[i]
        for c in range(k):
            state.throughput[i, c] = k * weight[i] if c == hero else 0.0
        state.flags[i] |= COLLAPSED
        if not weight[i] > 0.0:
            continue
        o = (origin[i, 0] - offset[0], origin[i, 1] - offset[1], origin[i, 2] - offset[2])
        for c in range(3):
            state.mis_origin[i, c] = o[c]
        queued += push_ray(state, rays, queued, i, o, (direction[i, 0], direction[i, 1], direction[i, 2]))
    return queued


def real_lens_camera(renderer, state, rays, first, count, samples_per_pixel, first_sample):
    xy = np.empty((count, 2))
    uv = np.empty((count, 2))
    hero_nm = np.empty(count)
    begin_lens_paths(state, renderer.camera.data, renderer.wavelengths, renderer.kernel_settings, renderer._pixels,
                     first, count, samples_per_pixel, first_sample, xy, uv, hero_nm)
    o, d, w = renderer.camera.lens.generate_rays(xy, uv, hero_nm[:, None])
    return finish_lens_paths(state, rays, count, np.ascontiguousarray(o), np.ascontiguousarray(d),
                             np.ascontiguousarray(w[:, 0]), renderer.camera.position)
