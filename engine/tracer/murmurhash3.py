"""MurmurHash3, x86 32-bit variant (Austin Appleby's public-domain algorithm): the hash Cryptomatte names
its ids with. Pure Python: a render hashes a few hundred names once, so speed does not matter, and the
extension then needs no compiled wheel for it (the ``mmh3`` package is the tests' oracle)."""

from __future__ import annotations

_C1, _C2 = 0xCC9E2D51, 0x1B873593
_MASK = 0xFFFFFFFF


def _rotl(x: int, r: int) -> int:
    return ((x << r) | (x >> (32 - r))) & _MASK


def _mix_block(k: int) -> int:
    k = (k * _C1) & _MASK
    return (_rotl(k, 15) * _C2) & _MASK


def murmurhash3_32(data: bytes | str, seed: int = 0) -> int:
    """The unsigned 32-bit hash of ``data`` (a str is hashed as its UTF-8 bytes, as Blender hashes names)."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    h = seed & _MASK
    body = len(data) - len(data) % 4
    for i in range(0, body, 4):
        h ^= _mix_block(int.from_bytes(data[i:i + 4], "little"))
        h = (_rotl(h, 13) * 5 + 0xE6546B64) & _MASK
    tail = data[body:]
    if tail:
        h ^= _mix_block(int.from_bytes(tail, "little"))
    h ^= len(data)
    # final avalanche
    h ^= h >> 16
    h = (h * 0x85EBCA6B) & _MASK
    h ^= h >> 13
    h = (h * 0xC2B2AE35) & _MASK
    return h ^ (h >> 16)
