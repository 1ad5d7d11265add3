"""Blender's Principled Hair BSDF as Cycles renders it: one ``HAIR`` closure (``tracer.bsdf.hair``) whose node
inputs go to its ``C_HAIR_*`` columns (constants) or are bound by the program (linked inputs), set up per hit
by ``tracer.materials.hair_setup`` as Cycles' ``svm/closure.h`` does.

Parametrizations (the node's ``parametrization``): ``COLOR`` (Direct Coloring: Color), ``MELANIN`` (Melanin,
Melanin Redness, Tint, Random Color) and ``ABSORPTION`` (Absorption Coefficient). The Huang model renders as
Chiang, with a warning naming what is left out. An unlinked Random is the strand's own random number
(Hair Info ▸ Random, ``export.hair_info``), as in Cycles. The (legacy) Hair BSDF is the same closure kind
with Cycles' ``bsdf_hair.h`` lobes.
"""

from __future__ import annotations

from ...tracer.bsdf.closure import (C_HAIR_COAT, C_HAIR_IOR, C_HAIR_MELANIN, C_HAIR_OFFSET, C_HAIR_RADIAL,
                                    C_HAIR_RANDOM, C_HAIR_RANDOM_COLOUR, C_HAIR_RANDOM_ROUGHNESS, C_HAIR_REDNESS,
                                    C_HAIR_ROUGHNESS, HAIR, SIGMA_ABSORPTION, SIGMA_COLOUR, SIGMA_MELANIN)
from ...tracer.bsdf.hair_kajiya import REFLECTION, TRANSMISSION
from .terms import COLOR, FLOAT, VECTOR, PendingClosure

SIGMA_MODES = {"COLOR": SIGMA_COLOUR, "ABSORPTION": SIGMA_ABSORPTION, "MELANIN": SIGMA_MELANIN}

#: (socket, ``C_HAIR_*`` column, ``HairInputs`` field) of the scalar inputs every parametrization reads.
SCALARS = (("Roughness", C_HAIR_ROUGHNESS, "roughness"), ("Radial Roughness", C_HAIR_RADIAL, "radial_roughness"),
           ("Coat", C_HAIR_COAT, "coat"), ("IOR", C_HAIR_IOR, "ior"), ("Offset", C_HAIR_OFFSET, "offset"),
           ("Random Roughness", C_HAIR_RANDOM_ROUGHNESS, "random_roughness"))
MELANIN_SCALARS = (("Melanin", C_HAIR_MELANIN, "melanin"), ("Melanin Redness", C_HAIR_REDNESS, "melanin_redness"),
                   ("Random Color", C_HAIR_RANDOM_COLOUR, "random_colour"))
HUANG_ONLY = ("Aspect Ratio", "Reflection", "Transmission", "Secondary Reflection")


def _non_negative(c, node, name, context):
    return c.vector_math("MAXIMUM", c.value(node, name, context, COLOR), c.const(0.0, 0.0, 0.0))


def principled_hair(c, node, context, weight):
    """Add the node's fibre closure, weighted by ``weight``."""
    if getattr(node, "model", "CHIANG") != "CHIANG":
        c.warn(node, "uses the Huang model; Prism renders the Chiang model instead (its "
                     + ", ".join(HUANG_ONLY) + " inputs are left out, Radial Roughness and Coat take their "
                     "values on the node).")
    mode = SIGMA_MODES.get(getattr(node, "parametrization", "COLOR"), SIGMA_COLOUR)
    scalars = SCALARS + (MELANIN_SCALARS if mode == SIGMA_MELANIN else ())
    hair = {column: (field, c.value(node, name, context, FLOAT)) for name, column, field in scalars}
    # Cycles: an unlinked Random is the strand's random number (its value on the node off strands)
    hair[C_HAIR_RANDOM] = ("random", c.value(node, "Random", context, FLOAT))
    strand_random = c.linked(node, "Random", context) is None
    s0 = s1 = None
    if mode == SIGMA_COLOUR:
        s0 = _non_negative(c, node, "Color", context)  # a reflectance: the table clips it at 1
    elif mode == SIGMA_MELANIN:
        s0 = _non_negative(c, node, "Tint", context)
    else:
        s1 = c.vector_math("MAXIMUM", c.value(node, "Absorption Coefficient", context, VECTOR),
                           c.const(0.0, 0.0, 0.0))
    c.add_closure(PendingClosure(HAIR, weight, node, s0=s0, s1=s1, hair=(mode, 0, hair, strand_random, None)))


def hair_bsdf(c, node, context, weight):
    """Blender's Hair BSDF: its Reflection or Transmission lobe (``tracer.bsdf.hair_kajiya``) about the curve's
    tangent (or its linked Tangent where that varies, as Cycles), weighted by Color."""
    # Cycles reads Tangent only where a link survives its constant folding: a constant one leaves the curve's
    tangent = c.value(node, "Tangent", context, VECTOR) if c.linked(node, "Tangent", context) is not None else None
    model = REFLECTION if getattr(node, "component", "Reflection") == "Reflection" else TRANSMISSION
    colour = _non_negative(c, node, "Color", context)
    scalars = (("Offset", C_HAIR_OFFSET, "offset"), ("RoughnessU", C_HAIR_ROUGHNESS, "roughness"),
               ("RoughnessV", C_HAIR_RADIAL, "radial_roughness"))
    hair = {column: (field, c.value(node, name, context, FLOAT)) for name, column, field in scalars}
    c.add_closure(PendingClosure(HAIR, c.weighted(weight, colour=colour), node,
                                 hair=(SIGMA_COLOUR, model, hair, False, tangent)))
