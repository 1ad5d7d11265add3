"""The Cryptomatte part of a film: per pixel, how many camera samples first hit each object and each
material (``stages.pass_writes.first_hit`` writes the indices + 1 of both, 0 for a sample that hit
nothing), turned into the ranked passes by ``cryptomatte.rank_images``.

Counts are integers, so the sums are exact whatever the order chunks arrive in: a chunked or threaded
render gives the same bits. A pixel keeps one entry per distinct object or material it saw (sparse:
a pixel inside a surface costs one), not the whole frame × ids.
"""

from __future__ import annotations

import numpy as np

from .cryptomatte import CryptomatteNames, name_hashes, pass_names, rank_images

OBJECT, MATERIAL = 0, 1  # the two index columns a sample writes (``PassLayout.cryptomatte`` and the next)
COLUMNS = 2
_INDEX_BITS = 32  # key = region pixel << 32 | index + 1


class CryptomatteFilm:
    """Counts for a region of ``pixels`` pixels."""

    def __init__(self, pixels: int):
        self.pixels = int(pixels)
        self._keys = [np.zeros(0, np.int64) for _ in range(COLUMNS)]
        self._counts = [np.zeros(0, np.int64) for _ in range(COLUMNS)]
        self._pending = [[] for _ in range(COLUMNS)]
        self._pending_size = 0

    def add(self, local_pixel: np.ndarray, indices: np.ndarray) -> None:
        """One chunk's samples: ``local_pixel`` [N] (region pixel), ``indices`` [N, 2] (object and
        material index + 1 of the first surface; 0: none)."""
        for column in range(COLUMNS):
            index = indices[:, column].astype(np.int64)
            hit = index > 0
            keys = (local_pixel[hit].astype(np.int64) << _INDEX_BITS) | index[hit]
            unique, counts = np.unique(keys, return_counts=True)
            self._pending[column].append((unique, counts))
            self._pending_size += len(unique)
        if self._pending_size > max(1 << 18, len(self._keys[OBJECT])):  # merging is O(entries): not every chunk
            self._merge()

    def _merge(self) -> None:
        for column in range(COLUMNS):
            if not self._pending[column]:
                continue
            keys = np.concatenate([self._keys[column]] + [k for k, _ in self._pending[column]])
            counts = np.concatenate([self._counts[column]] + [c for _, c in self._pending[column]])
            unique, inverse = np.unique(keys, return_inverse=True)
            self._keys[column] = unique
            self._counts[column] = np.bincount(inverse.ravel(), weights=counts, minlength=len(unique)).astype(np.int64)
            self._pending[column] = []
        self._pending_size = 0

    def entries(self, column: int):
        """(region pixel, index, samples) of every pixel and object (``OBJECT``) or material seen there."""
        self._merge()
        keys = self._keys[column]
        return keys >> _INDEX_BITS, (keys & ((1 << _INDEX_BITS) - 1)) - 1, self._counts[column]

    def images(self, kinds, levels: int, names: CryptomatteNames, samples: np.ndarray, shape) -> dict:
        """The passes of ``kinds`` (of ``cryptomatte.KINDS``) for a region of ``shape`` (h, w) whose
        pixels took ``samples`` [h · w] camera samples: name → float32 [h, w, 4]."""
        out = {}
        for kind in kinds:
            pixel, index, count = self.entries(MATERIAL if kind == "Material" else OBJECT)
            table = names.of_kind(kind)
            hashes = name_hashes(table)
            ids = hashes[np.clip(index, 0, len(hashes) - 1)] if len(hashes) else np.zeros(len(index), np.uint32)
            ranked = rank_images(pixel, ids, count, samples, levels).reshape(*shape, -1)
            for layer, name in enumerate(pass_names(kind, levels)):
                out[name] = ranked[..., 4 * layer:4 * layer + 4]
        return out

