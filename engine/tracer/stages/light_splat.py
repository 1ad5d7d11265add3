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


def add_pass_splats(total, total_sq, splats, pixels, rgb) -> int:
    """Add one pass's splats (``pixels`` int64 [N], ``rgb`` float64 [N, 3], in path order) to the sums
    ``total`` / ``total_sq`` [P, 3] and the splat counts ``splats`` [P]; returns how many were dropped as
    non-finite."""
    order = np.argsort(pixels, kind="stable")
    return int(splat(total, total_sq, splats, np.ascontiguousarray(pixels[order]), np.ascontiguousarray(rgb[order]),
                     len(pixels)))
