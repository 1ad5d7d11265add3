"""Reading float grids of OpenVDB files with the ``openvdb`` module Blender bundles.

Blender ships OpenVDB's Python module inside its own Python (on ``sys.path`` in Blender; the ``bpy`` module
from PyPI carries it in ``bpy/<version>/python/lib/python3.x/site-packages`` without putting that folder on
the path (``import bpy`` does not add it), so it is added here when the plain import fails). A grid becomes a dense float32 array over its
active voxels' bounding box and the affine map from that array's indices to the grid's (object) space.
"""

from __future__ import annotations

import glob
import os
import sys

import numpy as np


class GridUnreadable(Exception):
    """A grid Prism cannot read; the message says why (for the warning)."""


def openvdb_module():
    """OpenVDB's Python module, or None where neither Blender nor the bpy module ships it."""
    try:
        import openvdb

        return openvdb
    except ImportError:
        pass
    try:
        import bpy
    except ImportError:
        return None
    # bpy is <version>/scripts/modules/bpy; Blender's Python is <version>/python, a few folders up
    here = os.path.dirname(os.path.abspath(bpy.__file__))
    for _ in range(6):
        for folder in sorted(glob.glob(os.path.join(here, "python", "lib", "python3*", "site-packages"))):
            if glob.glob(os.path.join(folder, "openvdb*")) and folder not in sys.path:
                sys.path.append(folder)
        here = os.path.dirname(here)
    try:
        import openvdb

        return openvdb
    except ImportError:
        return None


def float_grid_names(path: str) -> list[str]:
    """The names of the float grids in the OpenVDB file ``path`` (empty when it cannot be read)."""
    vdb = openvdb_module()
    if vdb is None:
        return []
    try:
        return [grid.name for grid in vdb.readAllGridMetadata(path) if grid.valueTypeName == "float"]
    except Exception:  # noqa: BLE001 - a missing or damaged file: the caller warns
        return []


def _affine(transform) -> np.ndarray:
    """The 4x4 matrix of an OpenVDB linear transform (index → its space), from the images of four points."""
    origin = np.asarray(transform.indexToWorld((0.0, 0.0, 0.0)), dtype=np.float64)
    matrix = np.eye(4)
    matrix[:3, 3] = origin
    for axis in range(3):
        unit = [0.0, 0.0, 0.0]
        unit[axis] = 1.0
        matrix[:3, axis] = np.asarray(transform.indexToWorld(tuple(unit)), dtype=np.float64) - origin
    return matrix


def read_float_grid(path: str, name: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(values float32 [nx, ny, nz], index_to_object float64 [4, 4]) of float grid ``name`` of ``path`` over
    its active voxels (array index 0 is the first active voxel); None when the grid has no active voxel.
    Raises ``GridUnreadable`` saying why it cannot be read."""
    vdb = openvdb_module()
    if vdb is None:
        raise GridUnreadable("this Blender has no OpenVDB Python module to read it")
    try:
        grid = vdb.read(path, name)
    except Exception as error:  # noqa: BLE001 - openvdb raises KeyError, IOError, RuntimeError...
        raise GridUnreadable(f"OpenVDB cannot read grid '{name}' of {path} ({error})") from error
    if grid.valueTypeName != "float":
        raise GridUnreadable(f"grid '{name}' holds {grid.valueTypeName} values, not float")
    if not grid.transform.isLinear:  # a property of the bound Transform
        raise GridUnreadable(f"grid '{name}' has a frustum (non-linear) transform")
    low, high = grid.evalActiveVoxelBoundingBox()
    shape = tuple(int(h) - int(lo) + 1 for lo, h in zip(low, high))
    if grid.activeVoxelCount() == 0 or min(shape) < 1:
        return None
    values = np.zeros(shape, np.float32)
    grid.copyToArray(values, ijk=tuple(int(x) for x in low))
    shift = np.eye(4)
    shift[:3, 3] = low
    return values, _affine(grid.transform) @ shift
