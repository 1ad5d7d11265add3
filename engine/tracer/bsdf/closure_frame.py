"""A closure that shades with a normal of its own scatters in a frame of its own; a closure whose normal a
bump turned away from the smooth normal has Cycles' bump shadowing term.

Directions reach the BSDF functions in the material's shading frame (z = the material's normal). A closure
with ``C_FRAMED`` (its own normal: a Principled Coat Normal, shaders with different Normal inputs mixed in one
material, or a normal Cycles' Bump Map Correction raised; set per hit by ``materials.closure_normals``) carries
that normal in this frame, ``C_FRAME_X/Y/Z``. Its lobe is evaluated and sampled in a frame whose z is that
normal; the tangents are any that complete it (Prism's lobes are isotropic), and pdfs are unchanged by the
rotation.

``bump_shadowing`` is Cycles' ``bump_shadowing_term`` (``closure/bsdf.h``): light that reaches the closure's
side of its normal from the other side of the smooth normal ``C_SMOOTH_X/Y/Z`` is dropped (when evaluating
for any closure; when sampling, for diffuse-like ones: diffuse, sheen, translucent), and with Bump Map
Correction diffuse-like closures are softened towards that horizon by a GGX shadowing term whose roughness
grows with the bump's tilt.

``terminator_softening`` is Cycles' shadow terminator Shading Offset (``closure/bsdf.h``, ``shift_cos_in``, from
Appleseed): light arriving at angle θ from the closure's normal is weighted by cos(m θ) / cos θ (0 past
90° / m), m = ``C_TERMINATOR``, so shading falls to 0 before the geometric terminator.
"""

from __future__ import annotations

import math

from ..jit import kernel
from ..vec3 import tangents, to_local, to_world
from .closure import (C_BUMPED, C_FRAME_X, C_FRAME_Y, C_FRAME_Z, C_FRAMED, C_KIND, C_SMOOTH_X, C_SMOOTH_Y,
                      C_SMOOTH_Z, C_TERMINATOR, C_VIEW_COS, DIFFUSE, SHEEN, TRANSLUCENT)

BUMP_SOFTENED = 2.0  # ``C_BUMPED`` value where Bump Map Correction softens diffuse light (1: only the test)


@kernel
def has_own_frame(row):
    return row[C_FRAMED] > 0.0


@kernel
def closure_normal(row):
    """The closure's normal in the material's frame."""
    if row[C_FRAMED] > 0.0:
        return (row[C_FRAME_X], row[C_FRAME_Y], row[C_FRAME_Z])
    return (0.0, 0.0, 1.0)


@kernel
def into_closure_frame(row, v):
    """``v`` (material frame) in the closure's frame."""
    m = (row[C_FRAME_X], row[C_FRAME_Y], row[C_FRAME_Z])
    s, t = tangents(m)
    return to_local(v, s, t, m)


@kernel
def out_of_closure_frame(row, v):
    """``v`` (closure frame) back in the material's frame."""
    m = (row[C_FRAME_X], row[C_FRAME_Y], row[C_FRAME_Z])
    s, t = tangents(m)
    return to_world(v, s, t, m)


@kernel
def view_cosine(row, cos_material):
    """The view cosine the closure sees: about its own normal, or the material's ``cos_material``."""
    return row[C_VIEW_COS] if row[C_FRAMED] > 0.0 else cos_material


@kernel
def _ggx_g1(alpha2, cos_n):
    tan2 = max(1.0 / (cos_n * cos_n) - 1.0, 0.0)
    return 1.0 / (1.0 + 0.5 * (math.sqrt(1.0 + alpha2 * tan2) - 1.0))


@kernel
def bump_shadowing(row, wi, evaluating):
    """Factor on the closure's light from ``wi`` (material frame); 1 unless ``C_BUMPED``."""
    if not row[C_BUMPED] > 0.0:
        return 1.0
    kind = int(row[C_KIND])
    diffuse_like = kind == DIFFUSE or kind == SHEEN or kind == TRANSLUCENT
    n = closure_normal(row)
    smooth = (row[C_SMOOTH_X], row[C_SMOOTH_Y], row[C_SMOOTH_Z])
    cos_smooth_wi = smooth[0] * wi[0] + smooth[1] * wi[1] + smooth[2] * wi[2]
    cos_smooth_n = smooth[0] * n[0] + smooth[1] * n[1] + smooth[2] * n[2]
    cos_n_wi = n[0] * wi[0] + n[1] * wi[1] + n[2] * wi[2]
    if cos_smooth_wi * cos_smooth_n * cos_n_wi < 0.0 and (evaluating or diffuse_like):
        return 0.0
    if not diffuse_like or row[C_BUMPED] < BUMP_SOFTENED:
        return 1.0
    cos_i, cos_d = abs(cos_smooth_wi), abs(cos_smooth_n)
    if cos_d >= 1.0 or cos_i >= 1.0:
        return 1.0
    if cos_i < 1e-6:
        return 0.0
    alpha2 = min(max(0.125 * (1.0 / (cos_d * cos_d) - 1.0), 0.0), 1.0)
    return _ggx_g1(alpha2, cos_i)


@kernel
def terminator_softening(row, wi, evaluating):
    """Factor on the closure's light from ``wi`` (material frame); 1 unless ``C_TERMINATOR`` > 1. Cycles applies it
    when evaluating toward the closure's side of its normal, and when sampling a reflection (the callers' test)."""
    m = row[C_TERMINATOR]
    if not m > 1.0:
        return 1.0
    n = closure_normal(row)
    cos_in = n[0] * wi[0] + n[1] * wi[1] + n[2] * wi[2]
    if evaluating and cos_in < 0.0:
        return 1.0
    cos_in = min(cos_in, 1.0)
    if not cos_in > 0.0:
        return 0.0
    return max(math.cos(math.acos(cos_in) * m), 0.0) / cos_in
