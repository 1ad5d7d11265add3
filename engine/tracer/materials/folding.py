"""Running instructions whose inputs are constant once, when a material is compiled: the kernels'
interpreter on a stand-in hit (the instructions folded never read it)."""

from __future__ import annotations

import numpy as np

from ..bsdf.closure import CLOSURE_ROW
from ..geometry import Geometry, SurfaceArrays, no_motion
from ..textures.image import build_textures
from ..visibility import ALL_RAYS
from .layering import load_tables


def fold_evaluator():
    """``evaluate(instructions, registers)``: run ``instructions`` (int32 [N, INSTRUCTION]) on
    ``registers`` (float64, in place)."""
    from .program import run_program

    attributes = SurfaceArrays(np.zeros((0, 1, 3, 2), np.float32), np.zeros((0, 1, 3, 4), np.float32),
                               np.zeros((0, 1, 3, 4), np.float32), np.zeros(0, np.int32), np.zeros((0, 27)),
                               np.zeros(3), np.zeros((0, 3, 3), np.float32))
    geometry = Geometry(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.int32),
                        np.zeros(1, np.int32), np.zeros((0, 3, 3), np.float32), attributes,
                        np.full(1, ALL_RAYS, np.uint8), *no_motion())
    tables = load_tables()
    textures = build_textures([])
    rows = np.zeros((1, CLOSURE_ROW))
    up = (0.0, 0.0, 1.0)

    def evaluate(instructions, registers):
        # The argument types of the render kernels' calls without rays (emission, transparency), so both share
        # one compiled specialisation.
        run_program(np.ascontiguousarray(instructions, dtype=np.int32), np.int32(0), np.int32(len(instructions)),
                    registers, rows, tables, textures, geometry, np.int64(0), 0.25, 0.25, (0.25, 0.25, 0.0), up, up,
                    up, False, None)

    return evaluate
