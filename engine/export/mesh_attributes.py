"""Per-corner data node materials read from an evaluated mesh, with ``foreach_get`` (no Python loop over
its elements): UV maps (by name; "" is the active render map), colour and other attributes (by name; ""
is the render colour attribute), UV tangents (Blender's MikkTSpace, as Cycles uses for normal maps).

Everything comes out per triangle corner of ``mesh.loop_triangles`` ([T, 3, width] float32) so the
tracer interpolates it with the hit's barycentrics. A mesh without a requested map or attribute gets
zeros there (Blender reads 0 too).
"""

from __future__ import annotations

import numpy as np

_WIDTH = {"FLOAT": 1, "INT": 1, "BOOLEAN": 1, "INT8": 1, "FLOAT2": 2, "INT32_2D": 2, "FLOAT_VECTOR": 3,
          "FLOAT_COLOR": 4, "BYTE_COLOR": 4, "QUATERNION": 4}
_PROPERTY = {"FLOAT": "value", "INT": "value", "BOOLEAN": "value", "INT8": "value", "FLOAT2": "vector",
             "INT32_2D": "value", "FLOAT_VECTOR": "vector", "FLOAT_COLOR": "color", "BYTE_COLOR": "color",
             "QUATERNION": "value"}


def uv_layer(mesh, name):
    """UV map ``name`` of ``mesh``, or for "" the active render one (None where there is none)."""
    layers = mesh.uv_layers
    if name:
        return layers.get(name)
    return next((layer for layer in layers if layer.active_render), layers.active)


def corner_uvs(mesh, name, loops):
    """float32 [T, 3, 2] of UV map ``name`` at the corners ``loops`` [T * 3], or None if the mesh lacks it."""
    layer = uv_layer(mesh, name)
    if layer is None:
        return None
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    layer.uv.foreach_get("vector", uv)
    return uv.reshape(-1, 2)[loops].reshape(-1, 3, 2)


def corner_attribute(mesh, name, loops, triangle_vertices):
    """float32 [T, 3, 4] RGBA of attribute ``name`` (a colour attribute, a UV map or any float attribute:
    scalars fill r, g, b; alpha 1 unless the attribute has one), or None if the mesh lacks it.

    Byte colours come out scene-linear: their ``color`` property is Blender's sRGB → linear decode of the
    stored bytes (``color_srgb`` holds the encoded value), as Cycles reads them."""
    name = attribute_name(mesh, name)
    attribute = mesh.attributes.get(name) if name else None
    if attribute is None:
        layer = mesh.uv_layers.get(name) if name else None
        if layer is None:
            return None
        uv = corner_uvs(mesh, name, loops)
        return np.concatenate([uv, np.zeros_like(uv[..., :1]), np.ones_like(uv[..., :1])], axis=-1)
    rgba = attribute_rgba(attribute)
    if rgba is None:
        return None
    per_corner = _gather_per_corner(mesh, rgba, attribute.domain, loops, triangle_vertices)
    return None if per_corner is None else per_corner.reshape(-1, 3, 4)


def attribute_name(data, name: str) -> str:
    """The attribute an Attribute or Color Attribute node named ``name`` reads on ``data`` (a mesh, curves or
    point cloud): ``name`` itself, or for "" the render colour attribute ("" where there is none)."""
    if name:
        return name
    colours = data.color_attributes
    return colours.default_color_name or (colours.active_color.name if colours.active_color else "")


def domain_rgba(data, name: str, domains: tuple):
    """(the attribute, float32 [N, 4] RGBA of its elements) that a node reading ``name`` finds on ``data`` (curves
    or a point cloud) in one of ``domains``, or (None, None) where there is none of a type read as a colour."""
    name = attribute_name(data, name)
    attribute = data.attributes.get(name) if name else None
    if attribute is None or attribute.domain not in domains:
        return None, None
    rgba = attribute_rgba(attribute)
    return (attribute, rgba) if rgba is not None else (None, None)


def attribute_rgba(attribute):
    """float32 [N, 4] RGBA of each element of ``attribute`` (any geometry's): scalars fill r, g, b; alpha 1
    unless the attribute has one. None for a type Cycles does not read as a colour."""
    width = _WIDTH.get(attribute.data_type)
    if width is None:
        return None
    count = len(attribute.data)
    values = np.empty(count * width, np.float32)
    attribute.data.foreach_get(_PROPERTY[attribute.data_type], values)
    values = values.reshape(count, width)
    rgba = np.zeros((count, 4), np.float32)
    rgba[:, 3] = 1.0
    if width == 1:
        rgba[:, :3] = values
    else:
        rgba[:, :width] = values
    return rgba


def _gather_per_corner(mesh, values, domain, loops, triangle_vertices):
    """``values`` [N, width] of one attribute gathered to the T * 3 triangle corners, flat [T * 3, width],
    from any domain Cycles renders: a point's value at each corner's vertex (``triangle_vertices`` is
    [T, 3] or flat), a corner's directly, a face's at each corner of its loop triangles. None for other
    domains (edge attributes, which Cycles does not render either)."""
    if domain == "POINT":
        return values[np.asarray(triangle_vertices).reshape(-1)]
    if domain == "CORNER":
        return values[np.asarray(loops).reshape(-1)]
    if domain == "FACE":
        polygon = np.empty(len(mesh.loop_triangles), np.int32)
        mesh.loop_triangles.foreach_get("polygon_index", polygon)
        return np.repeat(values[polygon], 3, axis=0)
    return None


def corner_tangents(mesh, name, loops, vertices, triangles, uvs, normals, warn):
    """float32 [T, 3, 4]: unit UV tangent (object space) and bitangent sign at each corner, from Blender's
    MikkTSpace for UV map ``name``; per-triangle tangents from the UVs when Blender cannot (n-gons)."""
    layer = uv_layer(mesh, name)
    if layer is None:
        return None
    try:
        mesh.calc_tangents(uvmap=layer.name)
        tangent = np.empty(len(mesh.loops) * 3, np.float32)
        sign = np.empty(len(mesh.loops), np.float32)
        mesh.loops.foreach_get("tangent", tangent)
        mesh.loops.foreach_get("bitangent_sign", sign)
        out = np.concatenate([tangent.reshape(-1, 3)[loops], sign[loops, None]], axis=1).reshape(-1, 3, 4)
        mesh.free_tangents()
        return out
    except RuntimeError:
        warn()
    corners = vertices[triangles]
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    d1, d2 = uvs[:, 1] - uvs[:, 0], uvs[:, 2] - uvs[:, 0]
    det = d1[:, 0] * d2[:, 1] - d2[:, 0] * d1[:, 1]
    safe = np.where(np.abs(det) > 1e-20, det, 1.0)
    t = (e1 * d2[:, 1:2] - e2 * d1[:, 1:2]) / safe[:, None]
    b = (e2 * d1[:, 0:1] - e1 * d2[:, 0:1]) / safe[:, None]
    n = normals.reshape(-1, 3, 3)
    t = np.repeat(t[:, None], 3, axis=1)
    t = t - n * np.einsum("tci,tci->tc", n, t)[..., None]
    t /= np.maximum(np.linalg.norm(t, axis=-1, keepdims=True), 1e-20)
    handed = np.sign(np.einsum("tci,tci->tc", np.cross(n, t), np.repeat(b[:, None], 3, axis=1)))
    return np.concatenate([t, np.where(handed < 0, -1.0, 1.0)[..., None]], axis=-1).astype(np.float32)
