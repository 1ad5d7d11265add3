"""``RTCRayHit`` as Embree 4 lays it out (``include/embree4/rtcore_ray.h``), declared once.

One 16-byte-aligned record of 96 bytes: ``RTCRay`` (48 bytes) then ``RTCHit`` (36 bytes of fields,
padded to 48 by its 16-byte alignment; with ``RTC_MAX_INSTANCE_LEVEL_COUNT`` 1 an ``instPrimID`` may
sit in that padding, depending on how the library was built). ``rtcOccluded1`` takes the ``RTCRay``
alone, the first 48 bytes. Kernels see the record through two views of the same memory, float32 and
uint32 words, indexed by the word constants below (derived from the dtype, so they cannot disagree
with it).
"""

from __future__ import annotations

import numpy as np

RAY_FIELDS = [
    ("org_x", np.float32), ("org_y", np.float32), ("org_z", np.float32), ("tnear", np.float32),
    ("dir_x", np.float32), ("dir_y", np.float32), ("dir_z", np.float32), ("time", np.float32),
    ("tfar", np.float32), ("mask", np.uint32), ("id", np.uint32), ("flags", np.uint32),
]
HIT_FIELDS = [
    ("Ng_x", np.float32), ("Ng_y", np.float32), ("Ng_z", np.float32), ("u", np.float32), ("v", np.float32),
    ("primID", np.uint32), ("geomID", np.uint32), ("instID", np.uint32),
]
RAY_BYTES = 48  # sizeof(RTCRay)
RAY_HIT_BYTES = 96  # sizeof(RTCRayHit): RTCHit is RTC_ALIGN(16), so it starts at 48 and pads to 48
ALIGNMENT = 16

RAY_DTYPE = np.dtype(RAY_FIELDS, align=True)
RAY_HIT_DTYPE = np.dtype({"names": ["ray", "hit"],
                          "formats": [RAY_DTYPE, np.dtype(HIT_FIELDS, align=True)],
                          "offsets": [0, RAY_BYTES], "itemsize": RAY_HIT_BYTES})


def _word(record: np.dtype, part: str, field: str) -> int:
    offset = record.fields[part][1] + record[part].fields[field][1]
    return offset // 4


ORG_X = _word(RAY_HIT_DTYPE, "ray", "org_x")
TNEAR = _word(RAY_HIT_DTYPE, "ray", "tnear")
DIR_X = _word(RAY_HIT_DTYPE, "ray", "dir_x")
TIME = _word(RAY_HIT_DTYPE, "ray", "time")
TFAR = _word(RAY_HIT_DTYPE, "ray", "tfar")
MASK = _word(RAY_HIT_DTYPE, "ray", "mask")
RAY_ID = _word(RAY_HIT_DTYPE, "ray", "id")
FLAGS = _word(RAY_HIT_DTYPE, "ray", "flags")
NG_X = _word(RAY_HIT_DTYPE, "hit", "Ng_x")
U = _word(RAY_HIT_DTYPE, "hit", "u")
V = _word(RAY_HIT_DTYPE, "hit", "v")
PRIM_ID = _word(RAY_HIT_DTYPE, "hit", "primID")
GEOM_ID = _word(RAY_HIT_DTYPE, "hit", "geomID")
INST_ID = _word(RAY_HIT_DTYPE, "hit", "instID")

INVALID_ID = 0xFFFFFFFF  # RTC_INVALID_GEOMETRY_ID
ALL_MASK = 0xFFFFFFFF  # a ray that sees every geometry


def new_ray_hit_record() -> tuple[np.ndarray, np.ndarray]:
    """One ``RTCRayHit``'s memory, 16-byte aligned, as (float32 words, uint32 words) views of it.

    Each thread that traces needs its own record; the views keep the memory alive."""
    raw = np.zeros(RAY_HIT_BYTES + ALIGNMENT, np.uint8)
    start = (-raw.ctypes.data) % ALIGNMENT
    record = raw[start:start + RAY_HIT_BYTES]
    return record.view(np.float32), record.view(np.uint32)
