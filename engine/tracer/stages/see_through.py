"""How much a camera path sees through: the transparency of a surface's resolved closures (Cycles'
``surface_shader_transparency``), the probability that sampling goes straight through it, and what the path's
throughput kept of what lies behind the cut-outs it crossed."""

from __future__ import annotations

from ..bsdf.closure import C_KIND, C_WEIGHT, TRANSPARENT
from ..jit import inlined


@inlined
def see_through(rows, spectral, closures):
    """(T, q): the material's transparency (the see-through lobes' tint, averaged over the path's
    wavelengths, as Cycles averages its colour) and the probability that sampling takes one of them."""
    total = 0.0
    null = 0.0
    transparency = 0.0
    k = spectral.shape[2]
    for c in range(closures):
        total += rows[c, C_WEIGHT]
        if int(rows[c, C_KIND]) == TRANSPARENT:
            null += rows[c, C_WEIGHT]
            tint = 0.0
            for j in range(k):
                tint += spectral[c, 2, j]
            transparency += tint / k
    if closures == 1:  # one closure is sampled whatever its weight
        return transparency, 1.0 if null > 0.0 or int(rows[0, C_KIND]) == TRANSPARENT else 0.0
    return transparency, null / total if total > 0.0 else 0.0


@inlined
def surface_alpha(rows, spectral, closures):
    """The surface's alpha: 1 - its transparency, within 0..1 (Cycles' ``surface_shader_alpha``)."""
    transparency, _ = see_through(rows, spectral, closures)
    return min(max(1.0 - transparency, 0.0), 1.0)


@inlined
def mean_throughput(state, i):
    """Path ``i``'s throughput averaged over its wavelengths (Cycles' ``average(throughput)``)."""
    k = state.throughput.shape[1]
    total = 0.0
    for c in range(k):
        total += state.throughput[i, c]
    return total / k
