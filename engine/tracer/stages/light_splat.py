"""The film's light-traced sums: a pass's splats, summed per pixel, then added to the film once.

A light path lands on any pixel, so a pass's splats (every light chunk's, concatenated in chunk
order, each chunk in path order) are sorted by pixel with a stable sort — which keeps path order
within a pixel — and each pixel's run is summed before it is added to the film: the same float64
sums whatever the chunking or thread count, and a render cut into sample chunks sums pass totals as
one render does.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import kernel


@kernel
def _add_runs(total, total_sq, pixels, rgb, count):
    """Add each run of equal consecutive ``pixels`` (summed first) to ``total`` and its squares to
    ``total_sq``; returns how many splats were not finite (dropped)."""
    dropped = 0
    j = 0
    while j < count:
        p = pixels[j]
        r_sum = g_sum = b_sum = 0.0
        r_sq = g_sq = b_sq = 0.0
        while j < count and pixels[j] == p:
            r, g, b = rgb[j, 0], rgb[j, 1], rgb[j, 2]
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
        total[p, 0] += r_sum
        total[p, 1] += g_sum
        total[p, 2] += b_sum
        total_sq[p, 0] += r_sq
        total_sq[p, 1] += g_sq
        total_sq[p, 2] += b_sq
    return dropped


def add_pass_splats(total, total_sq, pixels, rgb) -> int:
    """Add one pass's splats (``pixels`` int64 [N], ``rgb`` float64 [N, 3], in path order) to the sums
    ``total`` / ``total_sq`` [P, 3]; returns how many were dropped as non-finite."""
    order = np.argsort(pixels, kind="stable")
    pixels = np.ascontiguousarray(pixels[order])
    rgb = np.ascontiguousarray(rgb[order])
    return int(_add_runs(total, total_sq, pixels, rgb, len(pixels)))
