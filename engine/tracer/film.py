"""The film: per-pixel running sums of RGB samples and their squares (float64), and sample counts.

Samples arrive already converted to scene-linear Rec.709 (the spectral-to-RGB map is linear, so the
mean of converted samples is the converted mean). ``add`` splats them one by one (``stages.film``):
non-finite samples are counted in ``nan_samples`` and dropped, the pixel's count still advancing.

Light tracing (``stages.light_paths``) adds a pass's splats separately (``add_light``): its estimate
of a pixel is the sum of its splats over the number of light paths traced, whichever pixel they hit,
and is added to the camera samples' mean.
"""

from __future__ import annotations

import numpy as np

from .stages.film import splat
from .stages.light_splat import add_pass_splats


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
        self.light_paths = 0  # light paths traced so far (the light splats' denominator)
        self._light_sum = self._light_sum_sq = self._light_splats = None

    def add(self, pixel_index: np.ndarray, rgb: np.ndarray) -> None:
        """Add one sample per entry: ``pixel_index`` [N] (y * width + x), ``rgb`` [N, 3]."""
        pixel_index = np.ascontiguousarray(pixel_index, dtype=np.int64)
        rgb = np.ascontiguousarray(rgb, dtype=np.float64).reshape(-1, 3)
        self.nan_samples += int(splat(self._sum, self._sum_sq, self._count, pixel_index, rgb, len(pixel_index)))

    def add_light(self, pixel_index: np.ndarray, rgb: np.ndarray, paths: int) -> None:
        """Add one pass's splats of ``paths`` light paths, in path order: ``pixel_index`` [N], ``rgb``
        [N, 3] (N <= paths)."""
        if self._light_sum is None:
            self._light_sum = np.zeros_like(self._sum)
            self._light_sum_sq = np.zeros_like(self._sum)
            self._light_splats = np.zeros_like(self._count)
        pixel_index = np.ascontiguousarray(pixel_index, dtype=np.int64)
        rgb = np.ascontiguousarray(rgb, dtype=np.float64).reshape(-1, 3)
        self.nan_samples += add_pass_splats(self._light_sum, self._light_sum_sq, self._light_splats, pixel_index, rgb)
        self.light_paths += int(paths)

    @property
    def counts(self) -> np.ndarray:
        """Samples per pixel, int64 [H, W]."""
        return self._count.reshape(self.height, self.width)

    def mean(self) -> np.ndarray:
        """Per-pixel mean, float64 [H, W, 3] (0 where no sample yet)."""
        n = np.maximum(self._count, 1)[:, None]
        mean = self._sum / n
        if self.light_paths:
            mean = mean + self._light_sum / self.light_paths
        return mean.reshape(self.height, self.width, 3)

    def variance_of_mean(self) -> np.ndarray:
        """Per-pixel variance of the mean estimate, float64 [H, W, 3]:
        unbiased sample variance / n (0 where fewer than 2 samples)."""
        n = self._count[:, None].astype(np.float64)
        safe = np.maximum(n, 2.0)
        mean = self._sum / np.maximum(n, 1.0)
        var = np.maximum(self._sum_sq - n * mean * mean, 0.0) / (safe - 1.0)
        var = np.where(n >= 2, var / safe, 0.0)
        if self.light_paths > 1:
            m = float(self.light_paths)
            var = var + np.maximum(self._light_sum_sq - self._light_sum ** 2 / m, 0.0) / (m * (m - 1.0))
        return var.reshape(self.height, self.width, 3)
