"""The film: per-pixel running sums of RGB samples and their squares (float64), sample counts, and the
sums of the requested passes' values (``aux`` columns, laid out by ``pass_table.FilmLayout``).

Samples arrive already converted to scene-linear Rec.709 (the spectral-to-RGB map is linear, so the
mean of converted samples is the converted mean). ``add`` splats them one by one (``stages.film``):
non-finite samples are counted in ``nan_samples`` and dropped, the pixel's count still advancing.

A film covers a rectangle of the frame (``region`` = x0, y0, x1, y1, rows from the top; default the whole
frame): a frame rendered tile by tile needs one tile's film at a time. Samples name their pixel by its
index in the frame (y · frame width + x), so a tile's image is the same as that part of a whole frame.

Light tracing (``stages.light_paths``) adds a pass's splats separately (``add_light``): its estimate of
a pixel is the sum of its splats over the number of light paths traced, whichever pixel they hit (those
outside the region are dropped), and is added to the camera samples' mean.

With a shadow catcher, Combined as Blender receives it (``combined``) and the Shadow Catcher pass are made
from Combined's sums and the catcher's columns (``shadow_catcher_film``).

Cryptomatte (``cryptomatte_film``) is summed beside, from the columns that follow the layout's film
columns in each sample's values (object, material, weight).
"""

from __future__ import annotations

import numpy as np

from .cryptomatte_film import COLUMNS as CRYPTOMATTE_COLUMNS
from .cryptomatte_film import CryptomatteFilm
from .frame_plan import film_bytes_per_pixel
from .shadow_catcher_film import WIDTH as CATCHER_WIDTH
from .shadow_catcher_film import combined_with_catcher, shadow_catcher_pass
from .stages.film import splat, splat_alpha
from .stages.light_splat import add_pass_splats


class Film:
    """Accumulates samples for a ``width`` x ``height`` frame (row 0 = top), or the ``region`` of it."""

    def __init__(self, width: int, height: int, layout=None, region=None):
        x0, y0, x1, y1 = region if region is not None else (0, 0, width, height)
        self.frame_width = int(width)
        self.frame_height = int(height)
        self.origin = (int(x0), int(y0))
        self.width = int(x1 - x0)
        self.height = int(y1 - y0)
        self.layout = layout
        count = self.width * self.height
        self._sum = np.zeros((count, 3))
        self._sum_sq = np.zeros((count, 3))
        self._count = np.zeros(count, dtype=np.int64)
        columns = layout.width if layout is not None else 0
        self._aux = np.zeros((count, columns))
        crypto = getattr(layout, "cryptomatte_column", -1)
        self.cryptomatte = CryptomatteFilm(count) if crypto >= 0 else None
        self._alpha = None  # sums of the samples' alpha, once a render has any transparency
        self.nan_samples = 0
        self.exposure = 1.0  # Film ▸ Exposure: scales what mean() and variance_of_mean() report, not the sums
        self.film_transparent = False  # Film ▸ Transparent (what Combined shows with a shadow catcher)
        self.light_paths = 0  # light paths traced so far (the light splats' denominator)
        self._light_sum = self._light_sum_sq = self._light_splats = None

    bytes_per_pixel = staticmethod(film_bytes_per_pixel)

    def add(self, pixel_index: np.ndarray, rgb: np.ndarray, aux: np.ndarray | None = None) -> None:
        """Add one sample per entry: ``pixel_index`` [N] (y * frame width + x), ``rgb`` [N, 3], ``aux``
        [N, layout width] (the passes' values of each sample)."""
        pixel_index = np.ascontiguousarray(pixel_index, dtype=np.int64)
        rgb = np.ascontiguousarray(rgb, dtype=np.float64).reshape(-1, 3)
        if aux is None:
            aux = np.zeros((len(pixel_index), self._aux.shape[1]))
        x0, y0 = self.origin
        self.nan_samples += int(splat(self._sum, self._sum_sq, self._count, self._aux, pixel_index, rgb, aux,
                                      len(pixel_index), self.frame_width, x0, y0, self.width))
        if self.cryptomatte is not None and aux.shape[1] > self.layout.cryptomatte_column:
            local = (pixel_index // self.frame_width - y0) * self.width + (pixel_index % self.frame_width - x0)
            first = self.layout.cryptomatte_column
            self.cryptomatte.add(local, aux[:, first:first + CRYPTOMATTE_COLUMNS])

    def add_alpha(self, pixel_index: np.ndarray, alpha: np.ndarray) -> None:
        """Add the alpha (1 - transparency) of the samples ``add`` just took, in the same order."""
        if self._alpha is None:
            self._alpha = np.zeros(len(self._count))
        pixel_index = np.ascontiguousarray(pixel_index, dtype=np.int64)
        x0, y0 = self.origin
        splat_alpha(self._alpha, pixel_index, np.ascontiguousarray(alpha, dtype=np.float64), len(pixel_index),
                    self.frame_width, x0, y0, self.width)

    def alpha(self) -> np.ndarray:
        """Per-pixel mean alpha, float64 [H, W] (1 where nothing was see-through)."""
        if self._alpha is None:
            return np.ones((self.height, self.width))
        n = np.maximum(self._count, 1)
        return np.where(self._count > 0, self._alpha / n, 1.0).reshape(self.height, self.width)

    def add_light_chunks(self, chunks) -> int:
        """Add a pass's light chunks, each (``pixel_index``, ``rgb``, paths), in chunk order; returns the paths."""
        paths = sum(count for _, _, count in chunks)
        self.add_light(np.concatenate([p for p, _, _ in chunks]), np.concatenate([c for _, c, _ in chunks]), paths)
        return paths

    def add_light(self, pixel_index: np.ndarray, rgb: np.ndarray, paths: int) -> None:
        """Add one pass's splats of ``paths`` light paths, in path order: ``pixel_index`` [N] (frame
        indices), ``rgb`` [N, 3] (N <= paths)."""
        if self._light_sum is None:
            self._light_sum = np.zeros_like(self._sum)
            self._light_sum_sq = np.zeros_like(self._sum)
            self._light_splats = np.zeros_like(self._count)
        pixel_index = np.ascontiguousarray(pixel_index, dtype=np.int64)
        rgb = np.ascontiguousarray(rgb, dtype=np.float64).reshape(-1, 3)
        x0, y0 = self.origin
        x, y = pixel_index % self.frame_width - x0, pixel_index // self.frame_width - y0
        inside = (x >= 0) & (x < self.width) & (y >= 0) & (y < self.height)
        self.nan_samples += add_pass_splats(self._light_sum, self._light_sum_sq, self._light_splats,
                                            pixel_index[inside], rgb[inside], self.frame_width, x0, y0, self.width)
        self.light_paths += int(paths)

    def in_frame(self, image: np.ndarray, fill: float = 0.0) -> np.ndarray:
        """``image`` [H, W, ...] of the region placed in a whole frame filled with ``fill`` (itself when
        the region is the frame)."""
        x0, y0 = self.origin
        if (x0, y0, self.width, self.height) == (0, 0, self.frame_width, self.frame_height):
            return image
        frame = np.full((self.frame_height, self.frame_width) + image.shape[2:], fill, image.dtype)
        frame[y0:y0 + self.height, x0:x0 + self.width] = image
        return frame

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
        return (mean * self.exposure).reshape(self.height, self.width, 3)

    @property
    def has_catcher(self) -> bool:
        """The scene has a shadow catcher: Combined is made from its accumulations (``combined``)."""
        return bool(getattr(self.layout, "catcher_objects", False))

    def _catcher_columns(self) -> np.ndarray:
        first = self.layout.kernel.catcher
        n = np.maximum(self._count, 1)[:, None]
        return (self._aux[:, first:first + CATCHER_WIDTH] / n).reshape(self.height, self.width, CATCHER_WIDTH)

    def shadow_catcher(self) -> np.ndarray:
        """Cycles' Shadow Catcher pass, float64 [H, W, 3] (1 where no catcher was seen; not exposed: a ratio)."""
        if self.layout is None or self.layout.kernel.catcher < 0:
            return np.ones((self.height, self.width, 3))
        n = np.maximum(self._count, 1)[:, None]
        combined = (self._sum / n).reshape(self.height, self.width, 3)
        return shadow_catcher_pass(combined, self.alpha(), self._catcher_columns())

    def combined(self) -> tuple[np.ndarray, np.ndarray]:
        """Combined as Blender receives it: (rgb float64 [H, W, 3] exposed, alpha float64 [H, W]) — ``mean`` and
        ``alpha``, or with a shadow catcher the matte Cycles writes (``shadow_catcher_film``: the shadow in
        alpha, or over the background, unless the Shadow Catcher pass is on)."""
        if not self.has_catcher:
            return self.mean(), self.alpha()
        approximate = "Shadow Catcher" not in self.layout.request.passes
        rgb, alpha = combined_with_catcher(self._catcher_columns(), self.shadow_catcher(), approximate,
                                           self.film_transparent)
        return rgb * self.exposure, alpha

    def aux_mean(self) -> np.ndarray:
        """The pass columns per pixel, float64 [H, W, layout width]: the mean of each over the samples."""
        n = np.maximum(self._count, 1)[:, None]
        return (self._aux / n).reshape(self.height, self.width, -1)

    def cryptomatte_images(self, names) -> dict[str, np.ndarray]:
        """The layout's Cryptomatte passes (none when off) with ids made of ``names``
        (``cryptomatte.CryptomatteNames``): name → float32 [H, W, 4]."""
        if self.cryptomatte is None:
            return {}
        request = self.layout.request
        return self.cryptomatte.images(request.cryptomatte, request.cryptomatte_levels, names, self._count,
                                       (self.height, self.width))

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
        var = var * self.exposure ** 2
        return var.reshape(self.height, self.width, 3)
