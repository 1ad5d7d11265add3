"""Each closure's normal at a hit, as Cycles sets its closures up (``svm/closure.h``).

A closure shades with its own normal where it has one (``C_NORMAL``: a register the program wrote, facing the
view like the material's normal), else with the material's. With Bump Map Correction on (Material ▸ Settings,
Cycles' default), a microfacet or translucent closure's normal is raised towards the geometric normal just
enough that its mirror reflection of the view leaves above the surface (``ensure_valid_specular_reflection``,
``bsdf_util.h``), wherever it differs from the geometric normal. ``set_up_normals`` finds each closure's normal
(world) and its view cosine before the layering and energy compensation read it; once the caller has the
shading frame, ``orient_closures`` expresses the normals in it (``bsdf.closure_frame``).
"""

from __future__ import annotations

import math

from ..bsdf.closure import (C_BUMPED, C_FRAME_X, C_FRAME_Y, C_FRAME_Z, C_FRAMED, C_KIND, C_NORMAL, C_SMOOTH_X,
                            C_SMOOTH_Y, C_SMOOTH_Z, C_VIEW_COS, CONDUCTOR, DIELECTRIC, SUBSURFACE, TRANSLUCENT,
                            C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ, HAIR)
from ..bsdf.closure_frame import BUMP_SOFTENED
from ..jit import kernel
from ..vec3 import tangents, to_local

SAME_NORMAL = 1.0 - 1e-7  # cosines above this are the same normal


@kernel
def _unit(x, y, z):
    length = math.sqrt(x * x + y * y + z * z)
    if not length > 0.0:
        return (0.0, 0.0, 0.0), False
    return (x / length, y / length, z / length), True


@kernel
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@kernel
def valid_specular_normal(ng, view, n):
    """Cycles' ``ensure_valid_specular_reflection``: ``n`` turned towards ``ng`` (in their plane) just enough that
    the reflection of ``view`` about it rises min(0.9 cos, 0.01) above the surface; ``n`` where it already does."""
    cos_v = _dot(view, n)
    r = (2.0 * cos_v * n[0] - view[0], 2.0 * cos_v * n[1] - view[1], 2.0 * cos_v * n[2] - view[2])
    iz = _dot(view, ng)
    threshold = min(0.9 * iz, 0.01)
    if _dot(ng, r) >= threshold:
        return n
    along = _dot(n, ng)
    x, valid = _unit(n[0] - along * ng[0], n[1] - along * ng[1], n[2] - along * ng[2])
    if not valid:
        x = n
    ix = _dot(view, x)
    a = ix * ix + iz * iz
    b = 2.0 * (a + iz * threshold)
    c = (threshold + iz) * (threshold + iz)
    root = math.sqrt(max(b * b - 4.0 * a * c, 0.0))
    nz2 = 0.25 * (b + root) / a if ix < 0.0 else 0.25 * (b - root) / a
    nx, nz = math.sqrt(max(1.0 - nz2, 0.0)), math.sqrt(max(nz2, 0.0))
    return (nx * x[0] + nz * ng[0], nx * x[1] + nz * ng[1], nx * x[2] + nz * ng[2])


@kernel
def _corrected(kind):
    """Whether Bump Map Correction raises this kind's normal (Cycles: microfacets, translucent, subsurface)."""
    return kind == CONDUCTOR or kind == DIELECTRIC or kind == TRANSLUCENT or kind == SUBSURFACE


@kernel
def set_up_normals(rows, count, regs, wo, ng, smooth, shading, correction):
    """Per closure: its normal (world) in ``C_FRAME_*`` and ``C_FRAMED`` where it is not the material's
    ``shading``; its view cosine ``C_VIEW_COS``; the smooth normal in ``C_SMOOTH_*`` and ``C_BUMPED`` where its
    normal is not ``smooth`` (``BUMP_SOFTENED`` with Bump Map Correction). ``wo``, ``ng``, ``smooth`` and
    ``shading`` face the view."""
    for c in range(count):
        n = shading
        if rows[c, C_NORMAL] >= 0.0:
            r = int(rows[c, C_NORMAL])
            own, valid = _unit(regs[r], regs[r + 1], regs[r + 2])
            if valid:
                n = own
        kind = int(rows[c, C_KIND])
        if correction and _corrected(kind) and _dot(n, ng) < SAME_NORMAL:
            n = valid_specular_normal(ng, wo, n)
        framed = _dot(n, shading) < SAME_NORMAL
        rows[c, C_FRAMED] = 1.0 if framed else 0.0
        rows[c, C_FRAME_X], rows[c, C_FRAME_Y], rows[c, C_FRAME_Z] = n[0], n[1], n[2]
        rows[c, C_VIEW_COS] = _dot(wo, n)
        bumped = _dot(n, smooth) < SAME_NORMAL
        rows[c, C_BUMPED] = (BUMP_SOFTENED if correction else 1.0) if bumped else 0.0
        rows[c, C_SMOOTH_X], rows[c, C_SMOOTH_Y], rows[c, C_SMOOTH_Z] = smooth[0], smooth[1], smooth[2]


@kernel
def orient_closures(rows, count, n, flipped):
    """The normals ``set_up_normals`` left in world space, in the frame ``tangents(n)`` of the material's shading
    normal ``n`` (``flipped``: ``n`` was turned to the back of a one-sided material, and they turn with it)."""
    s, t = tangents(n)
    sign = -1.0 if flipped else 1.0
    for c in range(count):
        if rows[c, C_FRAMED] > 0.0:
            m = (sign * rows[c, C_FRAME_X], sign * rows[c, C_FRAME_Y], sign * rows[c, C_FRAME_Z])
            rows[c, C_FRAME_X], rows[c, C_FRAME_Y], rows[c, C_FRAME_Z] = to_local(m, s, t, n)
        if rows[c, C_BUMPED] > 0.0:
            m = (sign * rows[c, C_SMOOTH_X], sign * rows[c, C_SMOOTH_Y], sign * rows[c, C_SMOOTH_Z])
            rows[c, C_SMOOTH_X], rows[c, C_SMOOTH_Y], rows[c, C_SMOOTH_Z] = to_local(m, s, t, n)
        if int(rows[c, C_KIND]) == HAIR:  # a fibre's tangent (``hair_setup``) does not turn with the normal's side
            m = (rows[c, C_HAIR_TX], rows[c, C_HAIR_TY], rows[c, C_HAIR_TZ])
            rows[c, C_HAIR_TX], rows[c, C_HAIR_TY], rows[c, C_HAIR_TZ] = to_local(m, s, t, n)
