"""The emitter's UV maps and byte colour attributes at the root of each particle hair strand, the values Cycles
gives particle hair (``ObtainCacheParticleUV`` and ``ObtainCacheParticleVcol`` in Blender's
``intern/cycles/blender/curves.cpp``): one value per strand, the same along it.

What Cycles reads there: every UV map of the emitter by name, the active render one for the default map (UV Map
node without a map, Texture Coordinate ▸ UV); and, by name, the colour attributes stored as bytes on face
corners (the legacy vertex colours), interpolated in sRGB and decoded (``color_srgb_to_linear_v4``). Any other
attribute (float colours, point-domain values, the default colour attribute) reads 0 on particle hair in Cycles,
and does in Prism (``uncarried`` names them for the warning).

Cycles interpolates at the face and weights Blender stored with each particle; bpy exposes neither for child
strands, so Prism takes the emitter's loop triangle nearest to each strand's root (the path cache's first point,
which Blender places on that face) with mathutils' BVH tree, and interpolates its corners barycentrically: the
same point on the same face, so the same value where the UVs are linear across the face (a quad's two triangles
agree with Blender's quad weights where it is a parallelogram in space and UV). A modifier after the particle
system that moves the surface (Subdivision) leaves the roots off the final surface; the nearest point there is
used.
"""

from __future__ import annotations

import numpy as np

from .mesh_attributes import attribute_name, uv_layer
from .nodes.colour_spaces import srgb_to_linear


def _nearest_triangles(mesh, roots: np.ndarray):
    """(corner loops [N, 3], barycentric weights [N, 3]) of the loop triangle of ``mesh`` nearest to each root
    [N, 3] (object space); None when the mesh has no triangle."""
    from mathutils.bvhtree import BVHTree

    mesh.calc_loop_triangles()
    count = len(mesh.loop_triangles)
    if count == 0:
        return None
    vertices = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", vertices)
    vertices = vertices.reshape(-1, 3).astype(np.float64)
    corners = np.empty(count * 3, np.int32)
    mesh.loop_triangles.foreach_get("vertices", corners)
    corners = corners.reshape(-1, 3)
    loops = np.empty(count * 3, np.int32)
    mesh.loop_triangles.foreach_get("loops", loops)
    tree = BVHTree.FromPolygons(vertices.tolist(), corners.tolist(), all_triangles=True)
    nearest = [tree.find_nearest(root) for root in roots.tolist()]
    triangle = np.array([hit[2] if hit[2] is not None else 0 for hit in nearest], np.int64)
    point = np.array([tuple(hit[0]) if hit[0] is not None else root for hit, root in zip(nearest, roots)],
                     np.float64).reshape(-1, 3)
    return loops.reshape(-1, 3)[triangle], barycentric(vertices[corners[triangle]], point)


def barycentric(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Weights [N, 3] of ``points`` [N, 3] in ``triangles`` [N, 3, 3] (the point projected onto each triangle's
    plane; a degenerate triangle gives its first corner the whole weight)."""
    a = triangles[:, 0]
    edge1, edge2, offset = triangles[:, 1] - a, triangles[:, 2] - a, points - a
    d11, d12, d22 = (edge1 * edge1).sum(1), (edge1 * edge2).sum(1), (edge2 * edge2).sum(1)
    o1, o2 = (offset * edge1).sum(1), (offset * edge2).sum(1)
    area = d11 * d22 - d12 * d12
    valid = area > 1e-30 * np.maximum(d11 * d22, 1e-300)
    safe = np.where(valid, area, 1.0)
    v = np.where(valid, (d22 * o1 - d12 * o2) / safe, 0.0)
    w = np.where(valid, (d11 * o2 - d12 * o1) / safe, 0.0)
    return np.column_stack([1.0 - v - w, v, w])


def _byte_corner_colour(mesh, name: str):
    attribute = mesh.attributes.get(name) if name else None
    if attribute is None or attribute.data_type != "BYTE_COLOR" or attribute.domain != "CORNER":
        return None
    srgb = np.empty(len(attribute.data) * 4, np.float32)
    attribute.data.foreach_get("color_srgb", srgb)
    return srgb.reshape(-1, 4)


def _uvs(mesh, name: str):
    layer = uv_layer(mesh, name)
    if layer is None:
        return None
    uv = np.empty(len(mesh.loops) * 2, np.float32)
    layer.uv.foreach_get("vector", uv)
    return uv.reshape(-1, 2)


def root_values(mesh, roots: np.ndarray, request) -> tuple[dict, dict, list]:
    """({slot: float32 [N, 4]}, {slot: float32 [N, 2]}, uncarried): the colour attributes and UV maps ``request``
    (``AttributeRequest``) names at each strand root [N, 3] on the emitter ``mesh`` (evaluated, object space),
    and the (kind, name) of the reads Cycles gives particle hair no value for though the emitter has them."""
    colors, uvs, uncarried = {}, {}, []
    if request is None or not (request.attributes or request.uvs) or len(roots) == 0:
        return colors, uvs, uncarried
    found = _nearest_triangles(mesh, roots)
    if found is None:
        return colors, uvs, uncarried
    loops, weights = found

    def at_roots(per_corner):
        return np.einsum("nk,nkc->nc", weights, per_corner[loops].astype(np.float64))

    for slot, name in request.uvs.items():
        per_corner = _uvs(mesh, name)
        if per_corner is not None:
            uvs[slot] = at_roots(per_corner).astype(np.float32)
    for slot, name in request.attributes.items():
        srgb, uv = _byte_corner_colour(mesh, name), _uvs(mesh, name) if name else None
        if srgb is not None:
            rgba = at_roots(srgb)
            rgba[:, :3] = srgb_to_linear(rgba[:, :3])
            colors[slot] = rgba.astype(np.float32)
        elif uv is not None:  # an Attribute node naming a UV map reads (u, v, 0)
            values = at_roots(uv)
            colors[slot] = np.column_stack([values, np.zeros(len(values)), np.ones(len(values))]).astype(np.float32)
        elif attribute_name(mesh, name) in mesh.attributes:
            uncarried.append(("attribute", name))
    return colors, uvs, uncarried
