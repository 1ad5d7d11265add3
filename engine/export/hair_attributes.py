"""The attributes node materials read on Hair Curves objects, per control point, for the round curves'
segments (``tracer.curves.CurveSegments.colors``).

Cycles reads a curve attribute of the point domain (a curve key) interpolated linearly along each segment by
the hit's curve parameter, and one of the curve domain as that strand's constant (``curve_attribute_float3``);
the tracer interpolates a segment's two ends the same way (``curves.corner_colors``). Values come out as the
mesh export gives them (``mesh_attributes``: scalars fill r, g, b; alpha 1 unless the attribute has one; byte
colours scene-linear). A strand without the attribute reads 0 (black, alpha 0), as in Cycles. UV maps are not
read (Cycles gives curves their surface's UV only through the "surface_uv_coordinate" attribute, which this
reads by name like any other).
"""

from __future__ import annotations

import numpy as np

from .mesh_attributes import attribute_rgba


def point_attributes(curves, request) -> dict:
    """{slot: float32 [P, 4]} of the attributes ``request`` names (``AttributeRequest.attributes``; "" is the
    default colour attribute) at each point of ``curves`` (``bpy.types.Curves``), for those it has on the
    point or curve domain."""
    out = {}
    if request is None:
        return out
    counts = None
    for slot, name in request.attributes.items():
        if not name:
            name = curves.color_attributes.default_color_name or (
                curves.color_attributes.active_color.name if curves.color_attributes.active_color else "")
        attribute = curves.attributes.get(name) if name else None
        if attribute is None or attribute.domain not in ("POINT", "CURVE"):
            continue
        rgba = attribute_rgba(attribute)
        if rgba is None:
            continue
        if attribute.domain == "CURVE":
            if counts is None:
                offsets = np.empty(len(curves.curves) + 1, np.int32)
                curves.curve_offset_data.foreach_get("value", offsets)
                counts = np.diff(offsets)
            rgba = np.repeat(rgba, counts, axis=0)
        out[slot] = rgba
    return out


def segment_colors(attributes: dict, point_kept, starts, instances: int) -> dict:
    """{slot: float32 [K * S, 2, 4]}: the ``attributes`` ({slot: [P, 4]}) at the two points of each segment of
    the kept points (``point_kept`` [P] bool; ``starts`` [S]: each segment's first kept point), repeated for
    ``instances`` instances."""
    out = {}
    for slot, values in attributes.items():
        kept = values[point_kept]
        ends = np.stack([kept[starts], kept[starts + 1]], axis=1)
        out[slot] = np.tile(ends, (instances, 1, 1)).astype(np.float32)
    return out


def stacked_colors(pieces: list, slot_count: int) -> np.ndarray | None:
    """float32 [A, C, 2, 4] of every piece's ``segment_colors`` (``pieces``: (segment count, {slot: values}) in
    the order the segments are assembled), zeros where a piece lacks a slot; None when no piece has any."""
    if slot_count == 0 or not any(colors for _, colors in pieces):
        return None
    out = np.zeros((slot_count, sum(n for n, _ in pieces), 2, 4), np.float32)
    start = 0
    for n, colors in pieces:
        for slot, values in colors.items():
            out[slot, start:start + n] = values
        start += n
    return out
