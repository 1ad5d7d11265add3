"""Cycles' Filter Glossy (``path_tricks``): a glossy surface reached by an unlikely path is shaded rougher.

Each path keeps the smallest solid-angle pdf of its non-specular bounces so far (``PathState.min_pdf``;
infinite at the camera, so the first surface is never blurred). At a later surface, with Cycles' value F
(``settings.filter_glossy`` holds 1 / F), blur_pdf = min_pdf / F; where it is below 1 every microfacet
lobe (Prism's conductors and dielectrics) gets a GGX alpha of at least sqrt(1 − blur_pdf) / 2, as Cycles'
``surface_shader.h`` and ``bsdf_microfacet_blur`` do. A mirror or clear glass seen after a diffuse bounce
becomes a rough one, and light sampling then reaches it: the caustic's fireflies become a blurred, less
noisy caustic. Energy compensation keeps the lobe's original roughness, as in Cycles (it is applied
before the blur). A Principled Hair fibre (Chiang) takes the same floor on its longitudinal variances and
azimuthal scale, as Cycles' ``bsdf_hair_chiang_blur`` does (the floor is compared with those, not with a
roughness); the Hair BSDF's lobes are not blurred, as in Cycles.
"""

from __future__ import annotations

import math

from ..bsdf.closure import (C_ALPHA, C_HAIR_M0, C_HAIR_MODEL, C_HAIR_S, C_HAIR_V, C_KIND, CONDUCTOR, DIELECTRIC,
                            HAIR, SMOOTH_ALPHA)
from ..jit import inlined


@inlined
def blur_alpha(settings, min_pdf):
    """The GGX alpha floor at a vertex of a path whose least likely bounce had pdf ``min_pdf`` (0: none)."""
    blur_pdf = settings.filter_glossy * min_pdf
    if blur_pdf >= 1.0:
        return 0.0
    return math.sqrt(1.0 - blur_pdf) * 0.5


@inlined
def blur_glossy_closures(rows, count, alpha_floor):
    """Raise the alpha of the ``count`` resolved microfacet closures (a Chiang fibre's variances and scale) to
    ``alpha_floor``; returns whether a lobe is rough now (light sampling must then run even at a material of
    perfect mirrors)."""
    if alpha_floor < SMOOTH_ALPHA:
        return False
    rough = False
    for c in range(count):
        kind = int(rows[c, C_KIND])
        if kind == CONDUCTOR or kind == DIELECTRIC:
            if rows[c, C_ALPHA] < alpha_floor:
                rows[c, C_ALPHA] = alpha_floor
            rough = True
        elif kind == HAIR and int(rows[c, C_HAIR_MODEL]) == 0:
            for column in (C_HAIR_V, C_HAIR_S, C_HAIR_M0):
                rows[c, column] = max(rows[c, column], alpha_floor)
    return rough
