"""Cryptomatte (the open standard Blender's compositor reads): ids of names, the passes' names and the
manifest, as Cycles writes them.

An id is the MurmurHash3_32 (seed 0) of a name, stored as the float32 with the hash's bits, except that a
hash whose exponent bits are all 0 or all 1 (a denormal, an infinity or a NaN) gets its lowest exponent
bit flipped (the standard's "uint32_to_float32"). Names are Cycles': the object's name (an instance: the
instanced object's), the material's name ("default_surface" for a slot without one) and, for the asset,
the name of the object's topmost parent (itself without a parent).

Per pixel, a kind (Object, Material, Asset) has ranks of (id, coverage), sorted by coverage, most
first; coverage is the fraction of the pixel's camera samples whose first surface has that id (the
background adds none). Levels (View Layer ▸ Passes ▸ Cryptomatte ▸ Levels) is the number of ranks kept,
made even: two ranks a four-channel pass, ``Crypto<Kind>00``, ``01``, ….
"""

from __future__ import annotations

import json
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from .murmurhash3 import murmurhash3_32

KINDS = ("Object", "Material", "Asset")
MAX_LEVELS = 16  # Blender's range for Levels (and Cycles' limit)
DEFAULT_LEVELS = 6
#: The name Cycles gives the material of a slot without one (its default surface shader).
DEFAULT_MATERIAL_NAME = "default_surface"
PASS_PREFIX = "Crypto"
#: A pass's channel ids: lowercase, as Cycles names them for the readers of other programs (the
#: Cryptomatte specification's ``.r .g .b .a``).
CHANNELS = "rgba"


def layers(levels: int) -> int:
    """Four-channel passes a kind needs for ``levels`` ranks (two ranks each, as Cycles rounds)."""
    return (min(MAX_LEVELS, max(1, int(levels))) + 1) // 2


def pass_names(kind: str, levels: int) -> list[str]:
    """Blender's names of a kind's passes: CryptoObject00, CryptoObject01, …"""
    return [f"{PASS_PREFIX}{kind}{i:02d}" for i in range(layers(levels))]


def hash_to_float(hashes) -> np.ndarray:
    """float32 ids of uint32 hashes (exponent 0 or 255: its lowest bit flipped, so never a denormal, an
    infinity or a NaN)."""
    bits = np.atleast_1d(np.asarray(hashes, np.uint64)).astype(np.uint32)
    exponent = (bits >> np.uint32(23)) & np.uint32(0xFF)
    flip = (exponent == 0) | (exponent == 0xFF)
    bits = np.where(flip, bits ^ np.uint32(1 << 23), bits)
    return bits.view(np.float32)


@lru_cache(maxsize=1 << 16)
def _name_hash(name: str) -> int:
    return murmurhash3_32(name)


def name_hashes(names) -> np.ndarray:
    """uint32 MurmurHash3_32 of each name (remembered: the passes are made again at every refresh of
    the image, and the pure-Python hash takes ~7 µs a name)."""
    return np.array([_name_hash(str(name)) for name in names], np.uint32)


def manifest(names) -> str:
    """The manifest: JSON of each distinct name → its hash as 8 hex digits, in first-seen order."""
    return json.dumps({str(n): f"{murmurhash3_32(str(n)):08x}" for n in names}, separators=(",", ":"),
                      ensure_ascii=False)


class CryptomatteNames(NamedTuple):
    """The names ids are made of: ``objects`` (per scene object), ``assets`` (per scene object: its
    topmost parent's name) and ``materials`` (per scene material)."""

    objects: tuple
    assets: tuple
    materials: tuple

    def of_kind(self, kind: str) -> tuple:
        return {"Object": self.objects, "Material": self.materials, "Asset": self.assets}[kind]


def scene_names(scene) -> CryptomatteNames:
    """The ``CryptomatteNames`` of a ``tracer.Scene``: its object names, the export's asset and material
    names (``DataPassInputs``), else the objects' own names and the materials' names."""
    inputs = scene.data_passes
    objects = tuple(scene.object_names) or ("Object",)
    assets = tuple(inputs.asset_names) if len(inputs.asset_names) == len(objects) else objects
    materials = tuple(inputs.material_names)
    if len(materials) != len(scene.materials):
        materials = tuple(m.name for m in scene.materials)
    return CryptomatteNames(objects, assets, materials)


def rank_images(pixel, ids, weight, samples, levels: int) -> np.ndarray:
    """Ranks of each pixel: ``pixel`` [N] (region pixel), ``ids`` uint32 [N] (hashes), ``weight`` [N]
    (samples with that pixel and id; pairs may repeat: they are summed), ``samples`` [P] (each pixel's
    sample count). Returns float32 [P, 4 · layers]: (id, coverage) pairs, coverage descending (equal
    coverages: the smaller hash first), (0, 0) past the last id."""
    slots = 2 * layers(levels)
    out = np.zeros((len(samples), 2 * slots), np.float32)
    pixel = np.asarray(pixel, np.int64)
    ids, weight = np.asarray(ids, np.int64), np.asarray(weight, np.float64)
    samples = np.asarray(samples, np.float64)
    single = np.bincount(pixel, minlength=len(samples))[pixel] == 1  # most pixels: nothing to sort
    _write_rank(out, pixel[single], np.zeros(int(single.sum()), np.int64), ids[single], weight[single], samples)
    if single.all():
        return out
    key = (pixel[~single] << 32) | ids[~single]
    unique, inverse = np.unique(key, return_inverse=True)
    total = np.bincount(inverse.ravel(), weights=weight[~single], minlength=len(unique))
    pix, hashes = unique >> 32, unique & 0xFFFFFFFF
    order = np.lexsort((hashes, -total, pix))
    pix, hashes, total = pix[order], hashes[order], total[order]
    rank = np.arange(len(pix)) - np.searchsorted(pix, pix, side="left")
    kept = rank < slots
    _write_rank(out, pix[kept], rank[kept], hashes[kept], total[kept], samples)
    return out


def _write_rank(out, pixel, rank, hashes, total, samples) -> None:
    """Rank ``rank`` of each ``pixel``: its id and coverage (``total`` of the pixel's ``samples``)."""
    out[pixel, 2 * rank] = hash_to_float(hashes)
    n = samples[pixel]
    out[pixel, 2 * rank + 1] = np.where(n > 0, total / np.maximum(n, 1.0), 0.0)
