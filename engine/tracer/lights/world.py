"""The world: constant background radiance color x strength (linear Rec.709,
upsampled as an illuminant spectrum). It is reached only by escaping rays
(BSDF sampling), never by next-event estimation, so its MIS weight is 1."""

from __future__ import annotations

import numpy as np


class WorldLight:
    def __init__(self, world, spectrum):
        self.strength = float(world.strength)
        self.black = self.strength == 0.0 or not any(c > 0 for c in world.color)
        self.spectrum = spectrum

    def escaped(self, d, lam):
        """Radiance [n,K] along escaping rays."""
        if self.black:
            return np.zeros(lam.shape)
        return self.strength * self.spectrum(lam)
