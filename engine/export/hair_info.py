"""What Cycles' Hair Info node reads of a strand, computed at export for every segment of the round curves:
Intercept (0 at the root to 1 at the tip, by length along the points), Length (the strand's, object space) and
Random (the strand's random number), as Cycles' Blender sync builds its curve attributes
(``ATTR_STD_CURVE_INTERCEPT``, ``ATTR_STD_CURVE_LENGTH``, ``ATTR_STD_CURVE_RANDOM``): lengths summed over the
polyline of the points in object space, Random = ``hash_uint2_to_float(curve index, 0)`` (Bob Jenkins' lookup3
final mix, ``util/hash.h``) of the curve's index in its Curves data-block. A segment keeps the intercept of its
two points; the kernels interpolate it along the segment (``tracer.curves``), as Cycles does a curve-key
attribute.
"""

from __future__ import annotations

import numpy as np

_SEED = np.uint32((0xDEADBEEF + (2 << 2) + 13) & 0xFFFFFFFF)


def _rotate(x, k):
    return (x << np.uint32(k)) | (x >> np.uint32(32 - k))


def hash_uint2_to_float(kx: np.ndarray, ky: int = 0) -> np.ndarray:
    """Cycles' ``hash_uint2_to_float`` of each of ``kx`` with ``ky``, vectorised (uint32 arithmetic wraps)."""
    with np.errstate(over="ignore"):
        a = np.asarray(kx, np.uint32) + _SEED
        b = np.full_like(a, _SEED) + np.uint32(ky)
        c = np.full_like(a, _SEED)
        for x, y, k in ((2, 1, 14), (0, 2, 11), (1, 0, 25), (2, 1, 16), (0, 2, 4), (1, 0, 14), (2, 1, 24)):
            state = [a, b, c]
            state[x] = (state[x] ^ state[y]) - _rotate(state[y], k)
            a, b, c = state
    return c.astype(np.float64) / float(0xFFFFFFFF)


def strand_info(points: np.ndarray, offsets: np.ndarray):
    """(intercept per point [P], length per curve [C], random per curve [C]) of strands in object space."""
    counts = np.diff(offsets)
    steps = np.zeros(len(points))
    if len(points) > 1:
        steps[1:] = np.linalg.norm(np.diff(points, axis=0), axis=1)
    steps[offsets[:-1][counts > 0]] = 0.0  # a strand's first point starts its length afresh
    along = np.cumsum(steps)
    start = np.repeat(along[offsets[:-1]], counts) if len(points) else along
    along = along - start
    length = np.zeros(len(counts))
    last = offsets[1:] - 1
    length[counts > 0] = along[last[counts > 0]]
    total = np.repeat(length, counts)
    intercept = np.divide(along, total, out=np.zeros_like(along), where=total > 0.0)
    return intercept, length, hash_uint2_to_float(np.arange(len(counts)))
