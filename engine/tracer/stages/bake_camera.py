"""Stage 1 for a bake: new paths whose first rays come from a table, one ray per pixel of the region.

A bake (Blender's Render ▸ Bake) shades the points of a surface that the texels of an image map to.
Cycles writes each texel's surface point as the camera ray's first hit; Prism instead starts a ray
just off the surface along its normal, pointing back at the point, so that the ordinary bounce loop
finds the baked point first and every later stage (emission, shading, light sampling, the light split
of the passes, the data passes) runs as for a camera ray. The rays are computed outside the kernels
(``engine.render.bake_points``) and handed over as a ``BakeRays`` table covering the region being
rendered; a pixel whose direction is (0, 0, 0) has no surface point and gets no path.

The ray does not move within the texel (Cycles jitters the barycentric coordinates within the texel's
footprint, staying inside the triangle): every sample of a texel starts from its centre.
"""

from __future__ import annotations

from collections import namedtuple

from ..jit import kernel
from .camera import draw_wavelengths, start_path
from .queue import push_ray

#: origin float64 [n, 3] (render space: world minus the render's origin, m), direction float64 [n, 3]
#: (unit; (0, 0, 0): no ray), time float64 [n] (the ray time, 0..1 of the shutter; Cycles bakes at 0.5),
#: for the pixels of the region x0, y0 .. x0 + width, row by row; frame_width: pixels per row of the
#: frame the pixel indices count in.
BakeRays = namedtuple("BakeRays", "origin direction time x0 y0 width frame_width")


@kernel
def bake_camera_kernel(state, rays, bake, ws, settings, pixels, first, count, samples_per_pixel, first_sample):
    """Start paths ``first .. first + count`` of the pass into rows 0 .. count-1 with the rays of ``bake``
    (``BakeRays``) and queue them. Returns the number of rays queued (pixels without a ray add nothing)."""
    queued = 0
    for i in range(count):
        p = first + i
        pixel = pixels[p // samples_per_pixel]
        sample = first_sample + p % samples_per_pixel
        ps = start_path(state, i, pixel, sample, settings.seed, settings.outside_medium)  # in the World's Volume, if any
        draw_wavelengths(state, i, ws, settings.sampler, ps, sample)
        row = (pixel // bake.frame_width - bake.y0) * bake.width + pixel % bake.frame_width - bake.x0
        d = (bake.direction[row, 0], bake.direction[row, 1], bake.direction[row, 2])
        if d[0] == 0.0 and d[1] == 0.0 and d[2] == 0.0:
            continue  # no surface point in this texel
        o = (bake.origin[row, 0], bake.origin[row, 1], bake.origin[row, 2])
        state.time[i] = bake.time[row]
        for c in range(3):
            state.mis_origin[i, c] = o[c]
        queued += push_ray(state, rays, queued, i, o, d)
    return queued
