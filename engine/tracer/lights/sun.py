"""Sun: a distant light of irradiance E (Blender's Strength, W/m^2) on a surface
facing it. With angular diameter 2 theta > 0 it is a uniform disk of radiance
E / (pi sin^2 theta), sampled uniformly in its cone and seen by escaping rays;
with angle 0 it is a delta direction."""

from __future__ import annotations

import numpy as np

from ..sampling import dot_vector, orthonormal_basis, to_world, uniform_cone


class SunLight:
    def __init__(self, light, spectrum):
        self.name = light.name
        d = np.asarray(light.direction, dtype=np.float64)
        self.to_sun = -d / np.linalg.norm(d)
        self.irradiance = float(light.irradiance_w_m2)
        self.spectrum = spectrum
        half = 0.5 * float(max(light.sun_angle_rad, 0.0))
        self.delta = half <= 0.0
        self.hittable = False
        self.distant = not self.delta
        if not self.delta:
            half = min(half, np.pi / 2)
            self.one_minus_cos = 2.0 * np.sin(half / 2.0) ** 2
            self.cos_max = 1.0 - self.one_minus_cos
            self.radiance = self.irradiance / (np.pi * np.sin(half) ** 2)
            s, t = orthonormal_basis(self.to_sun[None, :])
            self._frame = (s, t, self.to_sun[None, :])

    def sample(self, p, u, lam):
        n = len(p)
        if self.delta:
            wi = np.broadcast_to(self.to_sun, (n, 3)).copy()
            return wi, np.full(n, np.inf), self.irradiance * self.spectrum(lam), np.ones(n)
        local = uniform_cone(u[:, :2], self.cos_max)
        wi = to_world(local, *self._frame)
        pdf = np.full(n, 1.0 / (2.0 * np.pi * self.one_minus_cos))
        return wi, np.full(n, np.inf), self.radiance * self.spectrum(lam), pdf

    def escaped(self, d, lam):
        """Radiance [n,K] along escaping rays ``d`` (0 outside the sun's disk)."""
        inside = dot_vector(d, self.to_sun) >= self.cos_max
        return np.where(inside, self.radiance, 0.0)[:, None] * self.spectrum(lam)

    def pdf_escaped(self, d):
        inside = dot_vector(d, self.to_sun) >= self.cos_max
        return np.where(inside, 1.0 / (2.0 * np.pi * self.one_minus_cos), 0.0)
