"""The multispectral film: per pixel, the mean spectral radiance in wavelength bands across the visible
range (an optional output, written as a spectral EXR by ``engine.output.spectral_exr``).

Kept apart from the RGB film: it exists only when ``RenderSettings.spectral_band_nm`` > 0. Bands tile
360-830 nm, every wavelength a path carries, with the width nearest the setting that divides the
range evenly (10 nm → 47 bands). Chunks hand it (band, value) pairs per wavelength sample
(``stages.spectral_bins``), added on the main thread in chunk order: the image depends on the seed
only.
"""

from __future__ import annotations

import threading

import numpy as np

from .errors import PrismInputError
from .spectra.wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM
from .stages.spectral_bins import spectral_bins_kernel, spectral_splat

BAND_RANGE_NM = (1.0, 100.0)


def band_edges_nm(band_nm: float) -> np.ndarray:
    """Edges [B+1] of the bands that tile 360-830 nm with a width nearest ``band_nm``."""
    low, high = BAND_RANGE_NM
    if not low <= band_nm <= high:
        raise PrismInputError(
            f"Spectral output band width {band_nm:g} nm is outside {low:g}-{high:g} nm: set Render ▸ Prism ▸ "
            "Spectral Output ▸ Band Width within that range (10 nm gives 47 bands)."
        )
    bands = max(1, int(round((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / band_nm)))
    return np.linspace(VISIBLE_MIN_NM, VISIBLE_MAX_NM, bands + 1)


class SpectralFilm:
    """Sums of band radiance for a ``width`` x ``height`` image (row 0 = top)."""

    def __init__(self, width: int, height: int, band_nm: float):
        self.width, self.height = int(width), int(height)
        self.edges_nm = band_edges_nm(float(band_nm))
        self.bands = len(self.edges_nm) - 1
        self.band_nm = float(self.edges_nm[1] - self.edges_nm[0])
        self._sum = np.zeros((self.width * self.height, self.bands))
        self._count = np.zeros(self.width * self.height, np.int64)
        self._local = threading.local()
        self.dropped = 0

    @property
    def centres_nm(self) -> np.ndarray:
        """Band centres [B] in nm."""
        return 0.5 * (self.edges_nm[1:] + self.edges_nm[:-1])

    def record(self, state, count: int):
        """(band [n, K], value [n, K]) of a traced chunk's first ``count`` paths (any worker thread)."""
        k = state.wavelength.shape[1]
        scratch = getattr(self._local, "scratch", None)
        if scratch is None or scratch[0].shape[0] < count or scratch[0].shape[1] != k:
            scratch = self._local.scratch = (np.empty((count, k), np.int32), np.empty((count, k)))
        band_of, value = scratch
        spectral_bins_kernel(state, count, float(self.edges_nm[0]), self.band_nm, self.bands, band_of, value)
        return band_of[:count].copy(), value[:count].copy()

    def add(self, pixels, band_of, value) -> None:
        """Add one chunk's record (main thread, chunks in order)."""
        pixels = np.ascontiguousarray(pixels, dtype=np.int64)
        self.dropped += int(spectral_splat(self._sum, self._count, pixels, band_of, value, len(pixels)))

    def mean(self) -> np.ndarray:
        """Mean spectral radiance per band, float64 [H, W, B] (per nm, the units of the scene's emission)."""
        n = np.maximum(self._count, 1)[:, None]
        return (self._sum / n).reshape(self.height, self.width, self.bands)
