"""The Cryptomatte part of a film: per pixel, how many camera samples first hit each object and each
material (``stages.pass_writes.first_hit`` writes the indices + 1 of both, 0 for a sample that hit
nothing), turned into the ranked passes by ``cryptomatte.rank_images``.

Counts are integers, so the sums are exact whatever the order chunks arrive in: a chunked or threaded
render gives the same bits. Most pixels see one object: each pixel's first id is counted in dense
arrays (8 bytes a pixel and column), the others (pixels on edges) in sorted sparse (pixel, index) keys
merged now and then, so a pass costs about a sort of its own chunk's samples.
"""

from __future__ import annotations

import numpy as np

from .cryptomatte import CryptomatteNames, name_hashes, pass_names, rank_images

OBJECT, MATERIAL = 0, 1  # the two index columns a sample writes (``PassLayout.cryptomatte`` and the next)
COLUMNS = 2
BYTES_PER_PIXEL = 8 * COLUMNS  # the dense first id and its count, int32 each
_SHIFT = 32  # sparse key = region pixel << 32 | index + 1
_EMPTY = 0


class CryptomatteFilm:
    """Counts for a region of ``pixels`` pixels."""

    def __init__(self, pixels: int):
        self.pixels = int(pixels)
        self._first = np.zeros((COLUMNS, self.pixels), np.int32)  # index + 1 of the pixel's first id; 0: none yet
        self._first_count = np.zeros((COLUMNS, self.pixels), np.int32)
        self._keys = [np.zeros(0, np.int64) for _ in range(COLUMNS)]
        self._counts = [np.zeros(0, np.int64) for _ in range(COLUMNS)]
        self._pending = [[] for _ in range(COLUMNS)]
        self._pending_size = 0

    def add(self, local_pixel: np.ndarray, indices: np.ndarray) -> None:
        """One chunk's samples: ``local_pixel`` [N] (region pixel), ``indices`` [N, 2] (object and
        material index + 1 of the first surface; 0: none)."""
        local_pixel = np.asarray(local_pixel, np.int64)
        for column in range(COLUMNS):
            index = indices[:, column].astype(np.int32)
            hit = index > 0
            pixel, index = local_pixel[hit], index[hit]
            if not len(pixel):
                continue
            # runs of one pixel and index (a pixel's samples are consecutive in a chunk): no sorting
            start = np.flatnonzero(np.r_[True, (pixel[1:] != pixel[:-1]) | (index[1:] != index[:-1])])
            counts = np.diff(np.r_[start, len(pixel)])
            pixel, index = pixel[start], index[start]
            first, first_count = self._first[column], self._first_count[column]
            leading = np.r_[True, pixel[1:] != pixel[:-1]]  # a pixel with no id yet takes its chunk's first
            claim = leading & (first[pixel] == _EMPTY)
            first[pixel[claim]] = index[claim]
            dense = first[pixel] == index
            if dense.any():  # runs of the same pixel are consecutive: sum them before adding once a pixel
                runs = np.flatnonzero(np.r_[True, pixel[dense][1:] != pixel[dense][:-1]])
                first_count[pixel[dense][runs]] += np.add.reduceat(counts[dense], runs).astype(np.int32)
            if not dense.all():
                keys = (pixel[~dense] << _SHIFT) | index[~dense]
                self._pending[column].append((keys, counts[~dense]))
                self._pending_size += len(keys)
        if self._pending_size > max(1 << 16, len(self._keys[OBJECT])):  # merging is O(entries): not every chunk
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
        """(region pixel, index, samples) of every pixel and object (``OBJECT``) or material seen there
        (each pair once)."""
        self._merge()
        seen = np.flatnonzero(self._first[column] != _EMPTY)
        keys = self._keys[column]
        pixel = np.concatenate([seen, keys >> _SHIFT])
        index = np.concatenate([self._first[column][seen].astype(np.int64), keys & 0xFFFFFFFF]) - 1
        return pixel, index, np.concatenate([self._first_count[column][seen].astype(np.int64), self._counts[column]])

    def images(self, kinds, levels: int, names: CryptomatteNames, samples: np.ndarray, shape) -> dict:
        """The passes of ``kinds`` (of ``cryptomatte.KINDS``) for a region of ``shape`` (h, w) whose
        pixels took ``samples`` [h · w] camera samples: name → float32 [h, w, 4]."""
        out = {}
        for kind in kinds:
            pixel, index, count = self.entries(MATERIAL if kind == "Material" else OBJECT)
            hashes = name_hashes(names.of_kind(kind))
            ids = hashes[np.clip(index, 0, len(hashes) - 1)] if len(hashes) else np.zeros(len(index), np.uint32)
            ranked = rank_images(pixel, ids, count, samples, levels).reshape(*shape, -1)
            for layer, name in enumerate(pass_names(kind, levels)):
                out[name] = ranked[..., 4 * layer:4 * layer + 4]
        return out
