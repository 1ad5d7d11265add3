"""Blender's Light Path node: each output reads what the ray that reached the point was, at render time
(``tracer.materials.light_path`` keeps it per path, as Cycles defines it)."""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from ...tracer.materials.light_path import OUTPUTS
from .terms import FLOAT


def light_path(c, node, context, variant, identifier):
    if identifier not in OUTPUTS:  # an output a later Blender added (e.g. Portal Depth)
        c.warn(node, f"output {identifier} is not provided by Prism; it reads 0.")
        return {identifier: (c.const(0.0), FLOAT)}
    return {identifier: (c.hit(op.LIGHT_PATH, variant, mode=OUTPUTS.index(identifier), width=1), FLOAT)}


HANDLERS = {"ShaderNodeLightPath": light_path}
