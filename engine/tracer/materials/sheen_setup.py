"""Blender's microfiber sheen at a hit: each ``SHEEN`` closure's fitted LTC for this view direction.

The fit (``bsdf.sheen``) depends on the view cosine and the sheen roughness (``C_ALPHA``), so, as Cycles
does when it sets a sheen closure up (``bsdf_sheen_setup``), the coefficients a and b are written into the
closure's row (``C_SHEEN_A``, ``C_SHEEN_B``) and its tint is scaled by the fitted albedo, once per hit; the
lobe's sample weight is then the tint and its pdf the LTC density. A degenerate fit (albedo 0) leaves a
closure that reflects nothing and is never selected.
"""

from __future__ import annotations

from ..bsdf.closure import C_ALPHA, C_KIND, C_SHEEN_A, C_SHEEN_B, SHEEN
from ..bsdf.closure_frame import view_cosine
from ..bsdf.sheen import ltc_fit
from ..jit import inlined


@inlined
def set_up_sheen(table, rows, spectral, count, cos_o):
    """Fit every sheen closure among ``count`` resolved ones to the view cosine ``cos_o``; ``table`` is a
    ``bsdf.sheen.SheenTable``."""
    for c in range(count):
        if int(rows[c, C_KIND]) != SHEEN:
            continue
        mu = min(abs(view_cosine(rows[c], cos_o)), 1.0)
        a, b, albedo = ltc_fit(table, rows[c, C_ALPHA], mu)
        rows[c, C_SHEEN_A] = a
        rows[c, C_SHEEN_B] = b
        for k in range(spectral.shape[2]):
            spectral[c, 2, k] *= albedo
