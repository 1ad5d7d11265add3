"""The attributes and UV maps node materials read on Hair Curves objects, per control point, for the round
curves' segments (``tracer.curves.CurveSegments.colors`` and ``uvs``).

Cycles reads a curve attribute of the point domain (a curve key) interpolated linearly along each segment by
the hit's curve parameter, and one of the curve domain as that strand's constant (``curve_attribute_float3``);
the tracer interpolates a segment's two ends the same way (``curves.corner_rows``). Colours and other
attributes come out as the mesh export gives them (``mesh_attributes``: scalars fill r, g, b; alpha 1 unless
the attribute has one; byte colours scene-linear). A UV map is a 2D-vector attribute: the one of that name, or,
for the default map, the first 2D-vector attribute on the curve domain (Cycles 4.5 takes that one as the
standard UV, the "surface_uv_coordinate" Blender gives hair grown on a surface). A strand without what is read
reads 0 (black, alpha 0; UV (0, 0)), as in Cycles.
"""

from __future__ import annotations

import numpy as np

from .mesh_attributes import domain_rgba


def _per_point(curves, values, domain, counts):
    """``values`` of a point- or curve-domain attribute at each point ([P, width])."""
    if domain == "POINT":
        return values
    if counts[0] is None:
        offsets = np.empty(len(curves.curves) + 1, np.int32)
        curves.curve_offset_data.foreach_get("value", offsets)
        counts[0] = np.diff(offsets)
    return np.repeat(values, counts[0], axis=0)


def _uv_attribute(curves, name):
    if name:
        attribute = curves.attributes.get(name)
        return attribute if attribute is not None and attribute.data_type == "FLOAT2" else None
    return next((a for a in curves.attributes if a.data_type == "FLOAT2" and a.domain == "CURVE"), None)


def point_values(curves, request) -> tuple[dict, dict]:
    """({slot: float32 [P, 4]}, {slot: float32 [P, 2]}): the attributes and UV maps ``request`` names
    (``AttributeRequest``; "" is the default colour attribute or UV map) at each point of ``curves``
    (``bpy.types.Curves``), for those it has on the point or curve domain."""
    colors, uvs = {}, {}
    if request is None:
        return colors, uvs
    counts = [None]
    for slot, name in request.attributes.items():
        attribute, rgba = domain_rgba(curves, name, ("POINT", "CURVE"))
        if rgba is not None:
            colors[slot] = _per_point(curves, rgba, attribute.domain, counts)
    for slot, name in request.uvs.items():
        attribute = _uv_attribute(curves, name)
        if attribute is None or attribute.domain not in ("POINT", "CURVE"):
            continue
        uv = np.empty(len(attribute.data) * 2, np.float32)
        attribute.data.foreach_get("vector", uv)
        uvs[slot] = _per_point(curves, uv.reshape(-1, 2), attribute.domain, counts)
    return colors, uvs


def segment_ends(values: dict, point_kept, starts, instances: int) -> dict:
    """{slot: float32 [K * S, 2, width]}: ``values`` ({slot: [P, width]}) at the two points of each segment of
    the kept points (``point_kept`` [P] bool; ``starts`` [S]: each segment's first kept point), repeated for
    ``instances`` instances."""
    out = {}
    for slot, per_point in values.items():
        kept = per_point[point_kept]
        ends = np.stack([kept[starts], kept[starts + 1]], axis=1)
        out[slot] = np.tile(ends, (instances, 1, 1)).astype(np.float32)
    return out
