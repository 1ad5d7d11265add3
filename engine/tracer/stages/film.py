"""Stage 5: each path's spectral radiance as scene-linear Rec.709, and the film's running sums.

``film_kernel`` converts per path (CIE observer or Gaussian channels, ``spectra.wavelength_sampling``).
``splat`` adds a chunk's samples to the film pixel by pixel (a pass's samples of a pixel are consecutive
paths in one chunk, so a pixel's sum does not depend on how a pass was cut into chunks or threads);
non-finite samples are counted and dropped (the pixel's
count still advances: a dropped sample counts as 0, which keeps the mean unbiased when they are rare).
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..spectra.wavelength_sampling import radiance_to_rgb


@kernel
def film_kernel(state, count, ws, rgb):
    """``rgb[i]`` = Rec.709 of path ``i``'s radiance, for paths 0 .. count-1."""
    for i in range(count):
        r, g, b = radiance_to_rgb(ws, state.radiance[i], state.wavelength[i], state.wavelength_pdf[i])
        rgb[i, 0] = r
        rgb[i, 1] = g
        rgb[i, 2] = b


@kernel
def splat_alpha(total, pixels, alpha, count, frame_width, x0, y0, width):
    """Add ``alpha[j]`` to pixel ``pixels[j]`` for j < count (frame indices, as ``splat``; consecutive
    samples of a pixel summed first, so chunked renders merge to the same sums)."""
    j = 0
    while j < count:
        p = pixels[j]
        local = (p // frame_width - y0) * width + (p % frame_width - x0)
        run = 0.0
        while j < count and pixels[j] == p:
            run += alpha[j]
            j += 1
        total[local] += run


@kernel
def splat(total, total_sq, samples, aux_total, pixels, rgb, aux, count, frame_width, x0, y0, width):
    """Add ``rgb[j]`` (and the pass values ``aux[j]``) to pixel ``pixels[j]`` for j < count; returns how
    many samples were not finite. Pixels are frame indices; the film holds the rectangle whose top-left
    pixel is (x0, y0) and which is ``width`` pixels wide.

    A pixel's consecutive samples are summed first and their sum added to the film once (as the sum
    of a pass), so a render split into sample chunks (``Renderer.start_at_sample``) merges to the same
    float64 sums as one render: chunk boundaries never split a pixel's samples within a pass."""
    dropped = 0
    columns = aux_total.shape[1]
    j = 0
    while j < count:
        p = pixels[j]
        local = (p // frame_width - y0) * width + (p % frame_width - x0)
        r_sum = g_sum = b_sum = 0.0
        r_sq = g_sq = b_sq = 0.0
        run = 0
        first = j
        while j < count and pixels[j] == p:
            r, g, b = rgb[j, 0], rgb[j, 1], rgb[j, 2]
            run += 1
            j += 1
            if not (math.isfinite(r) and math.isfinite(g) and math.isfinite(b)):
                dropped += 1
                continue
            r_sum += r
            g_sum += g
            b_sum += b
            r_sq += r * r
            g_sq += g * g
            b_sq += b * b
        samples[local] += run
        total[local, 0] += r_sum
        total[local, 1] += g_sum
        total[local, 2] += b_sum
        total_sq[local, 0] += r_sq
        total_sq[local, 1] += g_sq
        total_sq[local, 2] += b_sq
        for c in range(columns):
            column_sum = 0.0
            for s in range(first, j):
                v = aux[s, c]
                if math.isfinite(v):
                    column_sum += v
            aux_total[local, c] += column_sum
    return dropped
