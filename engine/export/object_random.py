"""Object Info ▸ Random of an object that is not an instance, as Cycles computes it.

Blender gives instances a random id of their own (``DepsgraphObjectInstance.random_id``) but 0 to plain
objects; for those Cycles hashes the object's name: a multiplicative string hash (×37 per byte), then
Bob Jenkins' lookup3 final mix of (that hash, 0). Checked against Cycles' own Random output
(``tests/blender/test_node_materials_cycles.py``).
"""

from __future__ import annotations

_MASK = 0xFFFFFFFF


def _rotate(x: int, k: int) -> int:
    return ((x << k) | (x >> (32 - k))) & _MASK


def _final_mix(a: int, b: int, c: int) -> int:
    for x, y, k in ((2, 1, 14), (0, 2, 11), (1, 0, 25), (2, 1, 16), (0, 2, 4), (1, 0, 14), (2, 1, 24)):
        state = [a, b, c]
        state[x] = ((state[x] ^ state[y]) - _rotate(state[y], k)) & _MASK
        a, b, c = state
    return c


def name_random_id(name: str) -> int:
    """The 32-bit random id Cycles gives a non-instanced object called ``name``."""
    h = 0
    for byte in name.encode("utf-8"):
        h = (h * 37 + byte) & _MASK
    seed = (0xDEADBEEF + (2 << 2) + 13) & _MASK
    return _final_mix((seed + h) & _MASK, seed, seed)
