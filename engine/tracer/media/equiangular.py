"""Equiangular sampling of distances along a ray in a medium, toward a light (Kulla & Fajardo 2012,
"Importance Sampling Techniques for Path Tracing in Participating Media"): the density of a collision at s
is proportional to 1 / (h² + (s − Δ)²), Δ the distance along the ray to the point nearest the light and h
the light's distance from the ray, so single scattering near a point light is sampled where it is strong.
Distance sampling alone (by the scattering coefficient) has unbounded variance in a pixel whose rays pass
through a point light.

``media.segment`` mixes it with distance sampling (one-sample MIS, balance heuristic): half the segments
sample a distance, half pick a light as light sampling does (∝ its selection probability) and, if it has
a position (point, spot, sphere, area), sample equiangularly toward it, otherwise a distance. A light
with a position is a *positional* light here; the mixture's density at s sums every positional light's
equiangular density weighted by its selection probability.
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..lights.row import DISK, L_KIND, L_PX, L_PY, L_PZ, POINT, RECTANGLE, SPHERE

#: Rays passing closer than this (m) to a light take distance sampling for it (the density is a spike).
MIN_LIGHT_DISTANCE = 1e-7


@inlined
def _positional(kind):
    return kind == POINT or kind == SPHERE or kind == RECTANGLE or kind == DISK


@inlined
def light_line(lights, light, o, d):
    """(usable, Δ, h): the light's position projected on the ray ``o`` + s ``d`` (unit ``d``) and its
    distance from it; ``usable`` false for lights without a position or rays through the light."""
    row = lights.rows[light]
    if not _positional(int(row[L_KIND])):
        return False, 0.0, 0.0
    cx, cy, cz = row[L_PX] - o[0], row[L_PY] - o[1], row[L_PZ] - o[2]
    delta = cx * d[0] + cy * d[1] + cz * d[2]
    hx, hy, hz = cx - delta * d[0], cy - delta * d[1], cz - delta * d[2]
    h = math.sqrt(hx * hx + hy * hy + hz * hz)
    return h > MIN_LIGHT_DISTANCE, delta, h


@inlined
def _angles(delta, h, t):
    a = math.atan2(-delta, h)
    b = math.atan2(t - delta, h) if math.isfinite(t) else 0.5 * math.pi
    return a, b


@inlined
def equiangular_distance(delta, h, t, u):
    """A distance in [0, t) with density ∝ 1 / (h² + (s − Δ)²) (``t`` may be inf)."""
    a, b = _angles(delta, h, t)
    s = delta + h * math.tan(a + u * (b - a))
    return min(max(s, 0.0), t * (1.0 - 1e-12) if math.isfinite(t) else s)


@inlined
def equiangular_density(delta, h, t, s):
    a, b = _angles(delta, h, t)
    span = b - a
    if not span > 0.0:
        return 0.0
    x = s - delta
    return h / (span * (h * h + x * x))


@inlined
def positional_mixture(lights, o, d, t, s):
    """(Σ over positional lights of selection probability × equiangular density at ``s``, Σ of their
    selection probabilities)."""
    density = 0.0
    mass = 0.0
    for light in range(lights.select_prob.shape[0]):
        prob = lights.select_prob[light]
        if not prob > 0.0:
            continue
        usable, delta, h = light_line(lights, light, o, d)
        if usable:
            mass += prob
            density += prob * equiangular_density(delta, h, t, s)
    return density, mass


def has_positional_lights(lights) -> bool:
    """Whether some light of ``lights`` (``LightArrays``) that light sampling may pick has a position."""
    import numpy as np

    kinds = lights.rows[:, L_KIND].astype(int)
    picked = lights.select_prob[:len(kinds)] > 0.0
    return bool((np.isin(kinds, (POINT, SPHERE, RECTANGLE, DISK)) & picked).any())
