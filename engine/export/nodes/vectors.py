"""Nodes that read or bend the shading normal: Normal Map (tangent space from the UV map's tangents,
object and world space), Bump (the height compiled three times: at the point and a small step along
two surface directions), Displacement (a bump for the Bump Only and Both methods; the vector that moves the vertices for
Displacement Only and Both, ``tracer.materials.displacement``), Fresnel, Layer
Weight, Normal. Each handler returns {output identifier: (Value, kind)} (see ``compiler``)."""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from .inputs import needs_objects
from .terms import COLOR, FLOAT, VECTOR


def normal_input(c, node, context, variant, name="Normal"):
    """The register of a linked normal input, or None (the shading normal)."""
    if c.linked(node, name, context) is None:
        return None
    return c.value(node, name, context, VECTOR, variant)


def normal_map(c, node, context, variant, identifier):
    space = op.NORMAL_MAP_SPACES.index(node.space)
    slot = 0
    if space == 0:
        c.needs.add(("tangent", node.uv_map or ""))
        slot = c.slots.tangent(node.uv_map) if c.slots else 0
    if space in (1, 3):
        needs_objects(c)
    strength = c.value(node, "Strength", context, FLOAT, variant)
    colour = c.value(node, "Color", context, COLOR, variant)
    return {"Normal": (c.emit(op.NORMAL_MAP, [strength, colour, slot], mode=space, width=3), VECTOR)}


def bump(c, node, context, variant, identifier, height_name="Height"):
    normal = normal_input(c, node, context, variant)
    if variant != 0:
        c.warn(node, "feeds the height of another Bump; Prism uses its input normal there.")
        return {"Normal": (normal if normal is not None else c.normal(variant), VECTOR)}
    heights = [c.value(node, height_name, context, FLOAT, v) for v in (0, 1, 2)]
    strength = c.value(node, "Strength", context, FLOAT, variant)
    distance = c.value(node, "Distance", context, FLOAT, variant)
    out = c.emit(op.BUMP, [heights[0], heights[1], heights[2], strength, distance, normal], mode=int(node.invert),
                 width=3)
    return {"Normal": (out, VECTOR)}


def displacement_bump(c, socket):
    """The normal bent by the Material Output's Displacement (Blender's Bump Only method): the height is
    the displacement along the normal."""
    heights = []
    for variant in (0, 1, 2):
        vector = c.value_of_socket(socket, (), VECTOR, variant)
        heights.append(c.vector_math("DOT_PRODUCT", vector, c.normal(variant)))
    return c.emit(op.BUMP, [heights[0], heights[1], heights[2], c.const(1.0), c.const(1.0), None], width=3)


def displacement_method(material) -> str:
    """Material ▸ Settings ▸ Surface ▸ Displacement: "BUMP" (Blender's default), "DISPLACEMENT" or "BOTH"
    (Blender 4.1 moved it from Cycles' material settings to the material)."""
    method = getattr(material, "displacement_method", None)
    if method is None:
        method = getattr(getattr(material, "cycles", None), "displacement_method", "BUMP")
    return method if method in ("BUMP", "DISPLACEMENT", "BOTH") else "BUMP"


def true_displacement(c, socket):
    """The Material Output's Displacement vector, read at each vertex to move it (Displacement Only, Both);
    it is an object-space vector, so the object rows are exported (``tracer.materials.displacement``)."""
    needs_objects(c)
    return c.value_of_socket(socket, (), VECTOR, 0)


def displacement(c, node, context, variant, identifier):
    height = c.value(node, "Height", context, FLOAT, variant)
    midlevel = c.value(node, "Midlevel", context, FLOAT, variant)
    scale = c.value(node, "Scale", context, FLOAT, variant)
    normal = normal_input(c, node, context, variant)
    amount = c.math("MULTIPLY", c.math("SUBTRACT", height, midlevel), scale)
    if node.space != "OBJECT":
        c.warn(node, "is in world space; Prism treats it as object space.")
    return {"Displacement": (c.vector_math("SCALE", normal if normal is not None else c.normal(variant), s=amount),
                             VECTOR)}


def fresnel(c, node, context, variant, identifier):
    ior = c.value(node, "IOR", context, FLOAT, variant)
    normal = normal_input(c, node, context, variant)
    return {"Fac": (c.emit(op.FRESNEL, [ior, normal]), FLOAT)}


def layer_weight(c, node, context, variant, identifier):
    blend = c.value(node, "Blend", context, FLOAT, variant)
    normal = normal_input(c, node, context, variant)
    out = c.emit(op.LAYER_WEIGHT, [blend, normal], width=2)
    return {"Fresnel": (out.component(0), FLOAT), "Facing": (out.component(1), FLOAT)}


def normal_node(c, node, context, variant, identifier):
    direction = [float(x) for x in node.outputs["Normal"].default_value]
    length = sum(x * x for x in direction) ** 0.5 or 1.0
    stored = c.const(*[x / length for x in direction])
    incoming = c.value(node, "Normal", context, VECTOR, variant)
    return {"Normal": (stored, VECTOR), "Dot": (c.vector_math("DOT_PRODUCT", stored, incoming), FLOAT)}


HANDLERS = {
    "ShaderNodeNormalMap": normal_map,
    "ShaderNodeBump": bump,
    "ShaderNodeDisplacement": displacement,
    "ShaderNodeFresnel": fresnel,
    "ShaderNodeLayerWeight": layer_weight,
    "ShaderNodeNormal": normal_node,
}
