"""A path's vertex on a surface, as light sampling and BSDF sampling see it, and Cycles' rules for which
directions there carry light.

Cycles checks the geometric normal when it *samples* a direction (a reflection must leave on the view's
side of the surface, a transmission cross it) but not when it *evaluates* one for light sampling: checking
it there would darken smooth-shaded geometry at the shadow terminator (``bsdf_microfacet.h``,
``bsdf_sample``). Where a bump or normal map turns a closure's normal, its
``bump_shadowing_term`` applies per closure (``bsdf.closure_frame``).
"""

from __future__ import annotations

from collections import namedtuple

from ..jit import kernel

# ``p``, ``ng``: the point and geometric normal (world); ``frame``: (tangent, bitangent, n), the material's
# shading frame; ``wo_l``: the view direction in it; ``ns``: the smooth shading normal (before any bump), on the
# view's side (what the shadow terminator offset reads: ``terminator``).
SurfaceVertex = namedtuple("SurfaceVertex", "p ng frame wo_l ns")
# The material resolved at the vertex: closure ``rows``, their ``spectral`` values and glass ``eta``, how many
# (``count``), and whether the path carries its hero wavelength alone (``collapsed``).
ResolvedBsdf = namedtuple("ResolvedBsdf", "rows spectral eta count collapsed")


@kernel
def on_its_geometric_side(cos_og, cos_ig, transmitted):
    """A sampled direction that reflects stays on the view's side of the geometric surface; one that
    transmits crosses it."""
    return (cos_og * cos_ig > 0.0) != transmitted
