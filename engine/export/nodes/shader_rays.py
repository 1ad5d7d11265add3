"""Blender's Ambient Occlusion and Bevel nodes: a material tracing rays of its own at render time
(``tracer.materials.shader_rays``), compiled as Cycles' ``AmbientOcclusionNode`` and ``BevelNode`` are.

Both need to know which object a triangle belongs to (Only Local, Bevel's search of the hit object's own
surface), so they ask for the object rows. Light tracing is off in scenes whose materials trace
(``tracer.analysis``): a light path's hits cannot.
"""

from __future__ import annotations

from ...tracer.materials import opcodes as op
from ...tracer.materials.program_builder import Value
from .inputs import needs_objects
from .terms import COLOR, FLOAT, VECTOR
from .vectors import normal_input


def ambient_occlusion(c, node, context, variant, identifier):
    colour = c.value(node, "Color", context, COLOR, variant)
    distance = c.value(node, "Distance", context, FLOAT, variant)
    if c.linked(node, "Distance", context) is None and c.known(distance) == 0.0:
        distance = c.const(c.ao_distance)  # Cycles' NODE_AO_GLOBAL_RADIUS: the World's AO distance
    flags = (op.AO_ONLY_LOCAL if node.only_local else 0) | (op.AO_INSIDE if node.inside else 0)
    needs_objects(c)
    out = c.emit(op.AMBIENT_OCCLUSION, [distance, normal_input(c, node, context, variant), colour],
                 mode=int(node.samples) * op.AO_SAMPLES + flags, width=4)
    return {"AO": (out.component(0), FLOAT), "Color": (Value(out.register + 1, 3), COLOR)}


def bevel(c, node, context, variant, identifier):
    radius = c.value(node, "Radius", context, FLOAT, variant)
    needs_objects(c)
    out = c.emit(op.BEVEL, [radius, normal_input(c, node, context, variant)], mode=int(node.samples), width=3)
    return {"Normal": (out, VECTOR)}


HANDLERS = {"ShaderNodeAmbientOcclusion": ambient_occlusion, "ShaderNodeBevel": bevel}
