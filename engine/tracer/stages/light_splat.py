"""The film's light-traced sums: a pass's splats, summed per pixel, then added to the film once.

A light path lands on any pixel, so a pass's splats (every light chunk's, concatenated in chunk
order, each chunk in path order) are sorted by pixel with a stable sort — which keeps path order
within a pixel — and each pixel's run is summed before it is added to the film (``film.splat``): the
same float64 sums whatever the chunking or thread count, and a render cut into sample chunks sums pass
totals as one render does.
"""

from __future__ import annotations

import numpy as np

from .film import splat


def add_pass_splats(total, total_sq, splats, pixels, rgb, frame_width, x0, y0, width) -> int:
    """Add one pass's splats (``pixels`` int64 [N] frame indices inside the film's region, ``rgb`` float64
    [N, 3], in path order) to the sums ``total`` / ``total_sq`` [P, 3] and the splat counts ``splats``
    [P] of the region whose top-left pixel is (x0, y0) and which is ``width`` wide; returns how many
    were dropped as non-finite."""
    order = np.argsort(pixels, kind="stable")
    no_columns = np.zeros((len(total), 0))
    return int(splat(total, total_sq, splats, no_columns, np.ascontiguousarray(pixels[order]),
                     np.ascontiguousarray(rgb[order]), np.zeros((len(pixels), 0)), len(pixels), frame_width, x0, y0,
                     width))
