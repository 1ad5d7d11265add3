"""Values at the shutter's time steps (``export.motion``, ``export.hair_motion``): whether they move, and an
object's own fewer steps spread over the scene's."""

from __future__ import annotations

import numpy as np


def is_still(steps: np.ndarray) -> bool:
    """Whether ``steps`` [S, ...] holds the same values at every time step."""
    return bool(np.array_equal(steps, np.broadcast_to(steps[:1], steps.shape)))


def resample(steps: np.ndarray, own: int) -> np.ndarray:
    """``steps`` [S, ...] re-made from its ``own`` evenly spaced steps (a subset of the S, nested), linear
    between them: an object with fewer motion steps moves as Cycles interpolates it."""
    total = len(steps)
    stride = (total - 1) // (own - 1)
    kept = steps[::stride]
    x = np.linspace(0.0, own - 1, total)
    lo = np.minimum(x.astype(int), own - 2)
    f = (x - lo).reshape((-1,) + (1,) * (steps.ndim - 1))
    return (1.0 - f) * kept[lo] + f * kept[lo + 1]
