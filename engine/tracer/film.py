"""The film: per-pixel running mean and variance of RGB samples (float64).

Each sample is already converted to scene-linear Rec.709 by the integrator (the
spectral-to-RGB conversion is linear, so the mean of converted samples is the
converted mean). Sums and sums of squares are kept in float64 per pixel with a
per-pixel sample count; samples that are NaN or infinite never reach the sums:
they are counted (``nan_samples``) and the pixel's count still advances, which
keeps the estimator unbiased when they are rare (a dropped sample counts as 0).
"""

from __future__ import annotations

import numpy as np

from .sampling import rows_finite


class Film:
    """Accumulates samples for a ``width`` x ``height`` image (row 0 = top)."""

    def __init__(self, width: int, height: int):
        self.width = int(width)
        self.height = int(height)
        count = self.width * self.height
        self._sum = np.zeros((count, 3))
        self._sum_sq = np.zeros((count, 3))
        self._count = np.zeros(count, dtype=np.int64)
        self.nan_samples = 0

    def add(self, pixel_index: np.ndarray, rgb: np.ndarray) -> None:
        """Add one sample per entry: ``pixel_index`` [N] (y * width + x), ``rgb`` [N,3]."""
        pixel_index = np.asarray(pixel_index, dtype=np.int64)
        rgb = np.asarray(rgb, dtype=np.float64)
        bad = ~rows_finite(rgb)
        if bad.any():
            self.nan_samples += int(bad.sum())
            rgb = np.where(bad[:, None], 0.0, rgb)
        if len(pixel_index) == 0:
            return
        # a chunk covers a narrow range of pixels: bin over that range only
        lo = int(pixel_index.min())
        hi = int(pixel_index.max()) + 1
        local = pixel_index - lo
        self._count[lo:hi] += np.bincount(local, minlength=hi - lo)
        for c in range(3):
            self._sum[lo:hi, c] += np.bincount(local, weights=rgb[:, c], minlength=hi - lo)
            self._sum_sq[lo:hi, c] += np.bincount(local, weights=rgb[:, c] ** 2, minlength=hi - lo)

    @property
    def counts(self) -> np.ndarray:
        """Samples per pixel, int64 [H, W]."""
        return self._count.reshape(self.height, self.width)

    def mean(self) -> np.ndarray:
        """Per-pixel mean, float64 [H, W, 3] (0 where no sample yet)."""
        n = np.maximum(self._count, 1)[:, None]
        return (self._sum / n).reshape(self.height, self.width, 3)

    def variance_of_mean(self) -> np.ndarray:
        """Per-pixel variance of the mean estimate, float64 [H, W, 3]:
        unbiased sample variance / n (0 where fewer than 2 samples)."""
        n = self._count[:, None].astype(np.float64)
        safe = np.maximum(n, 2.0)
        mean = self._sum / np.maximum(n, 1.0)
        var = np.maximum(self._sum_sq - n * mean * mean, 0.0) / (safe - 1.0)
        var = np.where(n >= 2, var / safe, 0.0)
        return var.reshape(self.height, self.width, 3)
