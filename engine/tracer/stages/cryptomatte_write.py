"""What a camera path writes for Cryptomatte (``cryptomatte_film`` counts it): the object and material
(index + 1) of the surface it is attributed to, and the sample's weight there.

Cycles writes every surface a camera ray meets with weight (1 - its transparency) times what the cut-outs
before it let through, and goes on through cut-outs (Transparent BSDF, alpha). A Prism path takes one
lobe at each surface, so it carries that weight instead: crossing a cut-out (its see-through lobe chosen
with probability q, transparency T) multiplies the carried weight by T / q; taking another lobe ends the
attribution there with weight carried × (1 - T) / (1 - q). Each surface then gets Cycles' weight in
expectation, and an opaque surface seen directly exactly 1. A surface that is all see-through (q = 1,
e.g. a grey Transparent BSDF) is attributed with probability 1 - T by a number of its own. A camera
path that scatters in a medium first is attributed to nothing: the scattering ends its ``CAMERA_PATH``
flag, so no later surface writes (Cycles writes surfaces only, weighted by what the medium let through:
the paths that reach the surface).
"""

from __future__ import annotations

from ..bsdf.closure import SAMPLED_NULL
from ..jit import inlined
from ..sampler import sample_1d
from .see_through import see_through

#: The sampler slot of the attribution at an all see-through surface (+ the bounce): past any bounce's
#: slots and the AO pass's.
SLOT_CRYPTOMATTE = (1 << 20) + 16


@inlined
def cryptomatte_vertex(state, passes, layout, settings, i, depth, triangle, material, rows, spectral, closures,
                       sampled):
    """Camera path ``i`` took lobe ``sampled`` at this surface: attribute it here or carry the weight on.
    Columns from ``layout.cryptomatte``: object + 1, material + 1 (0: not attributed yet), weight (while
    not attributed: 1 - the weight carried, so a fresh path's 0 means 1)."""
    column = layout.cryptomatte
    if passes.row_object.shape[0] == 0 or passes.values[i, column] != 0.0:
        return
    carried = 1.0 - passes.values[i, column + 2]
    transparency, q = see_through(rows, spectral, closures)
    if sampled & SAMPLED_NULL:
        if q < 1.0:
            passes.values[i, column + 2] = 1.0 - carried * transparency / q
            return
        if sample_1d(settings.sampler, state.seed[i], state.sample[i], SLOT_CRYPTOMATTE + depth) < transparency:
            return  # the share that goes on: the weight carried is unchanged
        weight = carried
    else:
        weight = carried * (1.0 - transparency) / (1.0 - q) if q < 1.0 else carried
    passes.values[i, column] = passes.row_object[triangle] + 1.0
    passes.values[i, column + 1] = material + 1.0
    passes.values[i, column + 2] = weight

