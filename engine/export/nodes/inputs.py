"""Input nodes: Texture Coordinate, UV Map, Attribute, Color Attribute, Volume Info, Geometry, Object Info,
Tangent, Value, RGB. Each handler returns {output identifier: (Value, kind)} (see ``compiler``)."""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from .terms import COLOR, FLOAT, VECTOR


#: The mode of a Color Attribute node's read (the kernels ignore it): Cycles reads a Color Attribute node as 0
#: inside a volume, even a Volume object's grid of that name, where an Attribute node reads the grid
#: (``volume_density``).
COLOR_ATTRIBUTE_NODE = 1


def _uv_slot(c, name):
    c.needs.add(("uv", name or ""))
    return c.slots.uv(name) if c.slots else 0


def _attribute_slot(c, name):
    c.needs.add(("attribute", name or ""))
    return c.slots.attribute(name) if c.slots else 0


def needs_objects(c):
    c.needs.add(("objects", ""))
    if c.slots:
        c.slots.need_objects()


def uv(c, name, variant):
    return c.hit(op.UV, variant, slot=_uv_slot(c, name))


def generated(c, variant):
    needs_objects(c)
    return c.hit(op.GENERATED, variant)


def texture_coordinate(c, node, context, variant, identifier):
    if identifier == "Generated":
        return {"Generated": (generated(c, variant), VECTOR)}
    if identifier == "UV":
        if node.from_instancer:
            c.warn(node, "reads the instancer's UVs; Prism reads the object's own.")
        return {"UV": (uv(c, "", variant), VECTOR)}
    if identifier == "Object":
        if node.object is not None:
            c.warn(node, f"uses object '{node.object.name}' for Object coordinates; Prism uses each object's own "
                         "space.")
        needs_objects(c)
        return {"Object": (c.hit(op.OBJECT_COORDINATES, variant), VECTOR)}
    if identifier == "Normal":
        c.warn(node, "Normal output is given in world space (Blender: object space).")
        return {"Normal": (c.normal(variant), VECTOR)}
    if identifier == "Reflection":
        incoming = c.hit(op.INCOMING, variant)
        return {"Reflection": (c.vector_math("REFLECT", c.vector_math("SCALE", incoming, s=c.const(-1.0)),
                                             c.normal(variant)), VECTOR)}
    c.warn(node, f"{identifier} coordinates are not supported; Prism uses Generated coordinates.")
    return {identifier: (generated(c, variant), VECTOR)}


def uv_map(c, node, context, variant, identifier):
    if node.from_instancer:
        c.warn(node, "reads the instancer's UVs; Prism reads the object's own.")
    return {"UV": (uv(c, node.uv_map, variant), VECTOR)}


def attribute(c, node, context, variant, identifier):
    if node.attribute_type != "GEOMETRY":
        c.warn(node, f"reads a {node.attribute_type.lower().replace('_', ' ')} attribute, which Prism does not "
                     "export; it reads 0.")
        zero = c.const(0.0, 0.0, 0.0)
        return {"Color": (zero, COLOR), "Vector": (zero, VECTOR), "Fac": (c.const(0.0), FLOAT),
                "Alpha": (c.const(0.0), FLOAT)}
    rgba = c.hit(op.COLOR_ATTRIBUTE, variant, slot=_attribute_slot(c, node.attribute_name), width=4)
    colour = rgba.__class__(rgba.register, 3)
    fac = c.emit(op.VECTOR_TO_FLOAT, [colour])
    return {"Color": (colour, COLOR), "Vector": (colour, VECTOR), "Fac": (fac, FLOAT), "Alpha": (rgba.component(3), FLOAT)}


def volume_info(c, node, context, variant, identifier):
    """Cycles' Volume Info: the attributes "color", "density", "flame" and "temperature" (a Volume object's
    grids), as Cycles expands it into Attribute nodes (their Color and Fac outputs)."""
    name = {"Color": "color", "Density": "density", "Flame": "flame", "Temperature": "temperature"}[identifier]
    rgba = c.hit(op.COLOR_ATTRIBUTE, variant, slot=_attribute_slot(c, name), width=4)
    colour = rgba.__class__(rgba.register, 3)
    if identifier == "Color":
        return {identifier: (colour, COLOR)}
    return {identifier: (c.emit(op.VECTOR_TO_FLOAT, [colour]), FLOAT)}


def color_attribute(c, node, context, variant, identifier):
    rgba = c.hit(op.COLOR_ATTRIBUTE, variant, slot=_attribute_slot(c, node.layer_name), width=4,
                 mode=COLOR_ATTRIBUTE_NODE)
    return {"Color": (rgba.__class__(rgba.register, 3), COLOR), "Alpha": (rgba.component(3), FLOAT)}


def geometry(c, node, context, variant, identifier):
    if identifier == "Position":
        return {identifier: (c.hit(op.POSITION, variant), VECTOR)}
    if identifier == "Normal":
        return {identifier: (c.normal(variant), VECTOR)}
    if identifier == "True Normal":
        return {identifier: (c.hit(op.TRUE_NORMAL, variant), VECTOR)}
    if identifier == "Incoming":
        return {identifier: (c.hit(op.INCOMING, variant), VECTOR)}
    if identifier == "Parametric":
        return {identifier: (c.hit(op.PARAMETRIC, variant), VECTOR)}
    if identifier == "Backfacing":
        return {identifier: (c.hit(op.BACKFACING, variant, width=1), FLOAT)}
    if identifier == "Tangent":
        c.warn(node, "Tangent output (radial) is not supported; Prism uses the default UV map's tangent.")
        c.needs.add(("tangent", ""))
        slot = c.slots.tangent("") if c.slots else 0
        return {identifier: (c.hit(op.TANGENT, variant, slot=slot), VECTOR)}
    c.warn(node, f"{identifier} output is not supported; Prism takes 0.5 there.")
    return {identifier: (c.const(0.5), FLOAT)}


def object_info(c, node, context, variant, identifier):
    if identifier == "Material Index":
        return {identifier: (c.const(float(c.material.pass_index)), FLOAT)}
    needs_objects(c)
    field = {"Location": 0, "Color": 1, "Alpha": 2, "Object Index": 3, "Random": 5}[identifier]
    width = 3 if field < 2 else 1
    kind = VECTOR if field == 0 else (COLOR if field == 1 else FLOAT)
    return {identifier: (c.hit(op.OBJECT_INFO, variant, mode=field, width=width), kind)}


def point_info(c, node, context, variant, identifier):
    """Cycles' Point Info: the point's centre (world, m), radius (m), random number; 0 off point clouds."""
    field = {"Position": 0, "Radius": 1, "Random": 2}[identifier]
    return {identifier: (c.hit(op.POINT_INFO, variant, mode=field, width=3 if field == 0 else 1),
                         VECTOR if field == 0 else FLOAT)}


def hair_info(c, node, context, variant, identifier):
    """Cycles' Hair Info on a strand of round curves (``tracer.materials.hit_inputs.hair_info``); 0 elsewhere."""
    field = {"Is Strand": 0, "Intercept": 1, "Length": 2, "Thickness": 3, "Tangent Normal": 4, "Random": 5}[identifier]
    return {identifier: (c.hit(op.HAIR_INFO, variant, mode=field, width=3 if field == 4 else 1),
                         VECTOR if field == 4 else FLOAT)}


def tangent(c, node, context, variant, identifier):
    if node.direction_type != "UV_MAP":
        c.warn(node, "radial tangents are not supported; Prism uses the default UV map's tangent.")
        name = ""
    else:
        name = node.uv_map
    c.needs.add(("tangent", name or ""))
    slot = c.slots.tangent(name) if c.slots else 0
    return {"Tangent": (c.hit(op.TANGENT, variant, slot=slot), VECTOR)}


def value(c, node, context, variant, identifier):
    return {"Value": (c.const(float(node.outputs[0].default_value)), FLOAT)}


def rgb(c, node, context, variant, identifier):
    return {"Color": (c.const(*[float(x) for x in node.outputs[0].default_value[:3]]), COLOR)}


HANDLERS = {
    "ShaderNodeTexCoord": texture_coordinate,
    "ShaderNodeUVMap": uv_map,
    "ShaderNodeAttribute": attribute,
    "ShaderNodeVertexColor": color_attribute,
    "ShaderNodeVolumeInfo": volume_info,
    "ShaderNodeNewGeometry": geometry,
    "ShaderNodeObjectInfo": object_info,
    "ShaderNodePointInfo": point_info,
    "ShaderNodeHairInfo": hair_info,
    "ShaderNodeTangent": tangent,
    "ShaderNodeValue": value,
    "ShaderNodeRGB": rgb,
}
