"""A ray segment inside a homogeneous medium: its emission, then where (if anywhere) the path scatters (in a
grid medium, ``delta_tracking`` instead).

Along a segment of length t (the next surface) the radiance is ∫₀ᵗ T(s) [ε + σ_s L_s] ds + T(t) L_surface,
T(s) = exp(-σ_t s), per wavelength. The emission term is added in closed form, ε (1 - T(t)) / σ_t. The
rest is estimated by distance sampling with spectral MIS (one-sample balance heuristic over the path's
wavelengths, as in pbrt-v4 and Miller et al. 2019 "A null-scattering path integral formulation of light
transport"): a wavelength c is chosen uniformly, a distance s drawn from σ_s(c) exp(-σ_s(c) s), and each
wavelength k weighted by its own f_k over the mixture (1/K) Σ_j p_j. Distances follow the scattering
coefficient, not the extinction: absorption then only weights the path (exactly, T is analytic) instead
of ending it at random, so an absorbing medium (coloured glass) costs no noise at all, and a scattering
one scatters where it should. A collision before t scatters (weight σ_s,k T_k(s) / avg_j σ_s,j
exp(-σ_s,j s)); otherwise the path reaches the surface with weight T_k(t) / avg_j exp(-σ_s,j t). A
chromatic medium therefore adds no colour noise where one wavelength's coefficient would starve the
others. A path that carries only its hero wavelength (after dispersion) samples with it alone. The
wavelength is chosen afresh per segment, so each segment's estimate is unbiased on its own.
"""

from __future__ import annotations

import math

from ..jit import inlined
from ..lights.dispatch import pick_light
from ..sampler import medium_light_slot, medium_slot, sample_2d
from ..spectra.table import spectrum_value
from ..state import COLLAPSED
from .coefficients import coefficients_at
from .delta_tracking import track_grid_medium
from .equiangular import equiangular_distance, light_line, positional_mixture


@inlined
def _add_emission(state, i, media, spectra, medium, t, sigma_t):
    strength = media.emission_strength[medium]
    if not (strength > 0.0 and math.isfinite(t)):
        return
    sid = media.emission[medium]
    for k in range(sigma_t.shape[0]):
        s = sigma_t[k]
        length = -math.expm1(-s * t) / s if s > 0.0 else t
        state.radiance[i, k] += state.throughput[i, k] * strength * spectrum_value(spectra, sid, state.wavelength[i, k]) * length


@inlined
def _scatters(sigma_s, hero, collapsed):
    """Whether a carried wavelength (the hero alone once collapsed) has a scattering coefficient."""
    for c in range(sigma_s.shape[0]):
        if sigma_s[c] > 0.0 and (c == hero or not collapsed):
            return True
    return False


@inlined
def cross_medium(state, i, t, media, spectra, settings, depth, sigma_t, sigma_s, lights, f, p):
    """Path ``i``'s ray, inside its medium, reaches a surface at ``t`` (inf: none). Adds the medium's
    emission along it and returns where the path scatters (< t, throughput weighted for it) or inf (it
    reaches the surface, throughput weighted by the transmittance). ``sigma_t``, ``sigma_s``, ``f``, ``p``:
    scratch [K]. With ``settings.equiangular``, in a medium that scatters at the path's wavelengths, half the
    segments sample the collision equiangularly toward a light of ``lights`` (``equiangular``) and every weight
    divides by the two strategies' mixture. A grid medium (``MediaArrays.grid``) is crossed by delta tracking
    instead (``delta_tracking``)."""
    medium = state.medium[i]
    if media.grid[medium] >= 0:
        return track_grid_medium(state, i, t, media, spectra, settings, depth, sigma_t, sigma_s, f, p)
    lam = state.wavelength[i]
    k = lam.shape[0]
    coefficients_at(media, spectra, medium, lam, sigma_t, sigma_s)
    _add_emission(state, i, media, spectra, medium, t, sigma_t)
    collapsed = state.flags[i] & COLLAPSED != 0
    u_channel, u_distance = sample_2d(settings.sampler, state.seed[i], state.sample[i], medium_slot(depth))
    channel = state.hero[i] if collapsed else min(int(u_channel * k), k - 1)
    chosen = sigma_s[channel]
    s = -math.log1p(-u_distance) / chosen if chosen > 0.0 else math.inf
    o = (state.origin[i, 0], state.origin[i, 1], state.origin[i, 2])
    d = (state.direction[i, 0], state.direction[i, 1], state.direction[i, 2])
    # Only where the path's wavelengths can scatter: in a medium that only absorbs (coloured glass) an
    # equiangular collision weighs 0, so half the segments would end and the rest count double, and a gem's
    # chains of internal reflections (2^-n survive, x 2^n) would look darker at any affordable sample count.
    toward_lights = settings.equiangular and _scatters(sigma_s, state.hero[i], collapsed)
    if toward_lights:
        u_strategy, u_equiangular = sample_2d(settings.sampler, state.seed[i], state.sample[i],
                                              medium_light_slot(depth))
        if u_strategy >= 0.5:  # toward a light picked as light sampling picks one, if it has a position
            light, _ = pick_light(lights, 2.0 * u_strategy - 1.0)
            usable, delta, h = light_line(lights, light, o, d)
            if usable:
                s = equiangular_distance(delta, h, t, u_equiangular)
    scatters = s < t
    at = s if scatters else t
    # The mixture's density (a collision at s) or probability (no collision before t).
    mixture = 0.0
    for c in range(k):
        if collapsed and c != channel:
            continue
        survival = math.exp(-sigma_s[c] * at) if sigma_s[c] > 0.0 else 1.0
        mixture += sigma_s[c] * survival if scatters else survival
    if not collapsed:
        mixture /= k
    if toward_lights:
        # Distance sampling: half the segments, and the other half's picks of lights without a position.
        equiangular, positional = positional_mixture(lights, o, d, t, at)
        mixture *= 0.5 * (2.0 - positional)
        if scatters:
            mixture += 0.5 * equiangular
    for c in range(k):
        if not mixture > 0.0:
            state.throughput[i, c] = 0.0
            continue
        transmittance = math.exp(-sigma_t[c] * at) if sigma_t[c] > 0.0 else 1.0
        state.throughput[i, c] *= (sigma_s[c] * transmittance if scatters else transmittance) / mixture
    return s if scatters else math.inf
