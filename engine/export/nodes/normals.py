"""Normals of shader nodes, as Cycles takes them: a Normal (or Coat Normal) input counts where it is linked; a
Principled sheen leans towards the Coat Normal; Material ▸ Settings ▸ Bump Map Correction."""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from .terms import VECTOR


def shader_normal(c, node, context, name="Normal"):
    """The Value of ``node``'s linked normal input ``name``, or None (the surface's own normal)."""
    if c.linked(node, name, context) is None:
        return None
    return c.value(node, name, context, VECTOR)


def bump_map_correction(c) -> bool:
    """Material ▸ Settings ▸ Bump Map Correction (Cycles' option, on by default)."""
    return bool(getattr(getattr(c.material, "cycles", None), "use_bump_map_correction", True))


def towards(c, normal, other, amount):
    """normalize(mix(normal, other, amount)); ``normal`` None is the surface's."""
    start = normal if normal is not None else c.normal()
    mixed = c.emit(op.MIX_VECTOR, [amount, start, other, None, 0], width=3)
    return c.vector_math("NORMALIZE", mixed)
