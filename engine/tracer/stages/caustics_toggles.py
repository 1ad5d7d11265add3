"""Cycles' Reflective / Refractive caustics toggles (``path_tricks``) at a surface a diffuse reflection led
to: the closures they exclude are left out of the material there, for light and BSDF sampling alike.

As Cycles' ``svm/closure.h``: Reflective off drops glossy reflection (Glossy, Metallic, Anisotropic, the
Principled specular layer and coat: Prism's ``CONDUCTOR`` closures); Refractive off drops the Refraction
BSDF and a glass's transmission; a glass is dropped whole when both are off. A glass's reflection alone
(Reflective off, Refractive on) stays (warned at export). Called only where ``settings.caustics_filtered``.
"""

from __future__ import annotations

from ..bsdf.closure import C_FRESNEL, C_KIND, C_WEIGHT, CONDUCTOR, DIELECTRIC, REFRACTION_ONLY
from ..jit import inlined


@inlined
def _drop(rows, spectral, c):
    rows[c, C_WEIGHT] = 0.0
    spectral[c, 2, :] = 0.0  # the closure's tint: f and the sampled weight are 0


@inlined
def filter_caustic_closures(settings, rows, spectral, count):
    """Leave out the closures the caustics toggles exclude among the ``count`` resolved ones."""
    for c in range(count):
        kind = int(rows[c, C_KIND])
        if kind == CONDUCTOR:
            if not settings.caustics_reflective:
                _drop(rows, spectral, c)
        elif kind == DIELECTRIC and not settings.caustics_refractive:
            if int(rows[c, C_FRESNEL]) == REFRACTION_ONLY or not settings.caustics_reflective:
                _drop(rows, spectral, c)
            else:
                spectral[c, 1, :] = 0.0  # the glass's transmission tint: it reflects only
