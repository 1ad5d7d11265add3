"""The Cryptomatte part of a film: per pixel, the weight of the camera samples attributed to each object
and each material (``stages.cryptomatte_write`` writes per sample the object and material index + 1,
0 for none, and the weight: 1 for an opaque surface seen directly), turned into the ranked passes by
``cryptomatte.rank_images`` (coverage = summed weight / the pixel's samples).

A pixel's samples of a pass are consecutive paths of one chunk, and the sums are made in path order,
then in pass order: the same bits for any thread count or chunk size. Most pixels see one object: each
pixel's first id is summed in dense arrays (12 bytes a pixel and kind), the others (pixels on edges) in
sorted sparse (pixel, index) keys merged now and then, so a pass costs about one pass over its samples.
"""

from __future__ import annotations

import numpy as np

from .cryptomatte import CryptomatteNames, name_hashes, pass_names, rank_images

OBJECT, MATERIAL, WEIGHT = 0, 1, 2  # the columns a sample writes (from ``PassLayout.cryptomatte``)
COLUMNS = 3
ID_COLUMNS = 2  # object and material
BYTES_PER_PIXEL = 12 * ID_COLUMNS  # the dense first id (int32) and its summed weight (float64)
_SHIFT = 32  # sparse key = region pixel << 32 | index + 1
_EMPTY = 0


class CryptomatteFilm:
    """Weights for a region of ``pixels`` pixels."""

    def __init__(self, pixels: int):
        self.pixels = int(pixels)
        self._first = np.zeros((ID_COLUMNS, self.pixels), np.int32)  # index + 1 of the pixel's first id; 0: none
        self._first_weight = np.zeros((ID_COLUMNS, self.pixels))
        self._keys = [np.zeros(0, np.int64) for _ in range(ID_COLUMNS)]
        self._weights = [np.zeros(0) for _ in range(ID_COLUMNS)]
        self._pending = [[] for _ in range(ID_COLUMNS)]
        self._pending_size = 0

    def add(self, local_pixel: np.ndarray, values: np.ndarray) -> None:
        """One chunk's samples in path order: ``local_pixel`` [N] (region pixel), ``values`` [N, COLUMNS]
        (object and material index + 1, 0: none; weight)."""
        local_pixel = np.asarray(local_pixel, np.int64)
        for column in range(ID_COLUMNS):
            index = values[:, column].astype(np.int32)
            hit = index > 0
            pixel, index, weight = local_pixel[hit], index[hit], values[hit, WEIGHT]
            if not len(pixel):
                continue
            # runs of one pixel and index (a pixel's samples are consecutive in a chunk): no sorting
            start = np.flatnonzero(np.r_[True, (pixel[1:] != pixel[:-1]) | (index[1:] != index[:-1])])
            weight = np.add.reduceat(weight, start)
            pixel, index = pixel[start], index[start]
            first, first_weight = self._first[column], self._first_weight[column]
            leading = np.r_[True, pixel[1:] != pixel[:-1]]  # a pixel with no id yet takes its chunk's first
            claim = leading & (first[pixel] == _EMPTY)
            first[pixel[claim]] = index[claim]
            dense = first[pixel] == index
            if dense.any():  # runs of the same pixel are consecutive: sum them before adding once a pixel
                runs = np.flatnonzero(np.r_[True, pixel[dense][1:] != pixel[dense][:-1]])
                first_weight[pixel[dense][runs]] += np.add.reduceat(weight[dense], runs)
            if not dense.all():
                keys = (pixel[~dense] << _SHIFT) | index[~dense]
                self._pending[column].append((keys, weight[~dense]))
                self._pending_size += len(keys)
        if self._pending_size > max(1 << 16, len(self._keys[OBJECT])):  # merging is O(entries): not every chunk
            self._merge()

    def _merge(self) -> None:
        for column in range(ID_COLUMNS):
            if not self._pending[column]:
                continue
            keys = np.concatenate([self._keys[column]] + [k for k, _ in self._pending[column]])
            weights = np.concatenate([self._weights[column]] + [w for _, w in self._pending[column]])
            unique, inverse = np.unique(keys, return_inverse=True)
            self._keys[column] = unique  # bincount sums in array order: older entries first, as they came
            self._weights[column] = np.bincount(inverse.ravel(), weights=weights, minlength=len(unique))
            self._pending[column] = []
        self._pending_size = 0

    def entries(self, column: int):
        """(region pixel, index, summed weight) of every pixel and object (``OBJECT``) or material seen
        there (each pair once)."""
        self._merge()
        seen = np.flatnonzero(self._first[column] != _EMPTY)
        keys = self._keys[column]
        pixel = np.concatenate([seen, keys >> _SHIFT])
        index = np.concatenate([self._first[column][seen].astype(np.int64), keys & 0xFFFFFFFF]) - 1
        return pixel, index, np.concatenate([self._first_weight[column][seen], self._weights[column]])

    def images(self, kinds, levels: int, names: CryptomatteNames, samples: np.ndarray, shape) -> dict:
        """The passes of ``kinds`` (of ``cryptomatte.KINDS``) for a region of ``shape`` (h, w) whose
        pixels took ``samples`` [h · w] camera samples: name → float32 [h, w, 4]."""
        out = {}
        for kind in kinds:
            pixel, index, weight = self.entries(MATERIAL if kind == "Material" else OBJECT)
            hashes = name_hashes(names.of_kind(kind))
            ids = hashes[np.clip(index, 0, len(hashes) - 1)] if len(hashes) else np.zeros(len(index), np.uint32)
            ranked = rank_images(pixel, ids, weight, samples, levels).reshape(*shape, -1)
            for layer, name in enumerate(pass_names(kind, levels)):
                out[name] = ranked[..., 4 * layer:4 * layer + 4]
        return out
