"""Blender's sheen as Cycles renders it: the Principled BSDF's Sheen layer and the Sheen BSDF node, both the
microfiber sheen of Zeltner, Burley & Chiang 2022 (``tracer.bsdf.sheen``).

Principled (Cycles ``svm/closure.h``, ``principled_bsdf_emission``): the sheen is the top layer, under
Alpha only. Its closure takes the running weight × Sheen Weight × Sheen Tint; everything below (coat,
emission, metal, glass, specular, diffuse) keeps weight × saturate(1 - max over channels of
(Sheen Weight × Sheen Tint × fitted albedo(view cosine, Sheen Roughness))) — Cycles' ``closure_layering_weight``
takes the largest channel, so the scale is one number per hit, not a spectrum.
"""

from __future__ import annotations

from ...tracer.bsdf.closure import SHEEN
from ...tracer.materials import opcodes as op
from .normals import shader_normal
from .terms import COLOR, FLOAT, PendingClosure


def principled_sheen(c, node, context, weight, cos, normal):
    """Add the Principled node's sheen closure (if any) above ``weight``; returns the weight left below it.
    ``cos`` is the view cosine register, ``normal`` the node's normal (None: the surface's)."""
    amount = c.math("MAXIMUM", c.value(node, "Sheen Weight", context, FLOAT), c.const(0.0))
    if c.known(amount) == 0.0:
        return weight
    roughness = c.clamp01(c.value(node, "Sheen Roughness", context, FLOAT))
    tint = c.vector_math("MAXIMUM", c.value(node, "Sheen Tint", context, COLOR), c.const(0.0, 0.0, 0.0))
    c.add_closure(PendingClosure(SHEEN, c.weighted(weight, scale=amount, colour=tint), node, alpha=roughness,
                                 normal=normal))
    largest = c.math("MAXIMUM", c.math("MAXIMUM", tint.component(0), tint.component(1)), tint.component(2))
    albedo = c.emit(op.SHEEN_ALBEDO, [roughness, cos])
    reflected = c.math("MULTIPLY", c.math("MULTIPLY", amount, largest), albedo)
    return c.weighted(weight, scale=c.clamp01(c.one_minus(reflected)))


def sheen_bsdf(c, node, context, weight):
    """Blender's Sheen BSDF node: Color × the microfiber lobe of Roughness. Blender's older Ashikhmin velvet
    is not modelled; it renders as microfiber, with a warning."""
    distribution = getattr(node, "distribution", "MICROFIBER")
    if distribution != "MICROFIBER":
        c.warn(node, f"uses the {distribution.title()} distribution; Prism renders the Microfiber sheen instead.")
    colour = c.vector_math("MAXIMUM", c.value(node, "Color", context, COLOR), c.const(0.0, 0.0, 0.0))
    roughness = c.clamp01(c.value(node, "Roughness", context, FLOAT))
    c.add_closure(PendingClosure(SHEEN, c.weighted(weight, colour=colour), node, alpha=roughness,
                                 normal=shader_normal(c, node, context)))
