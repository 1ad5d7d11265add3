"""What every BSDF returns, in the local shading frame (+Z = normal).

Directions point away from the surface. ``eval(wo, wi, lam)`` gives f [n,K]
(without the cosine) and the solid-angle pdf [n] of ``sample``; delta lobes
evaluate to 0. ``sample(wo, lam, u [n,3], hero [n], collapsed [n])`` returns a
``BSDFSample``; ``weight`` = f |cos wi| / pdf per wavelength column.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class BSDFSample:
    wi: np.ndarray  # [n,3] local, unit
    weight: np.ndarray  # [n,K]
    pdf: np.ndarray  # [n] solid angle (inf for delta lobes)
    delta: np.ndarray  # [n] bool
    eta_scale: np.ndarray  # [n] (n_i/n_t)^-2 factor of refraction, for Russian roulette

    @classmethod
    def empty(cls, n, k):
        return cls(np.zeros((n, 3)), np.zeros((n, k)), np.zeros(n), np.zeros(n, dtype=bool), np.ones(n))


class BSDF:
    """Base: opaque, two-sided, non-delta, non-dispersive."""

    delta = False  # every lobe is a delta: no next-event estimation
    two_sided = True  # the frame is flipped so that wo.z > 0
    disperses = False  # outgoing directions depend on wavelength: keep the hero only
    kind = "bsdf"

    def eval(self, wo, wi, lam, hero=None, collapsed=None):
        raise NotImplementedError

    def sample(self, wo, lam, u, hero, collapsed):
        raise NotImplementedError


def hero_column(values: np.ndarray, hero: np.ndarray) -> np.ndarray:
    """values[i, hero[i]] for [n,K] arrays."""
    return values[np.arange(len(hero)), hero]
