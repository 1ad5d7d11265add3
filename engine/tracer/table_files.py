"""Precomputed tables shipped as .npz files (``tools/generate_*.py``), read once per process into a record."""

from __future__ import annotations

from functools import cache

import numpy as np


@cache
def load_table(path, record):
    """``record`` (a named tuple type) of the arrays of ``path`` named as its fields, contiguous float64."""
    with np.load(path) as data:
        return record(*(np.ascontiguousarray(data[name], dtype=np.float64) for name in record._fields))
