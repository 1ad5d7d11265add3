"""Point and spot lights, optionally with a soft radius (then a sphere light).

Units as Cycles: a light of power P has radiant intensity I = P / (4 pi) W/sr
times its luminance-normalised spectrum (spots too, then cut by the cone). With
``radius_m`` = r > 0 it is a sphere of radiance I / (pi r^2), which is hit by
rays and sampled uniformly in the cone it subtends.
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot, dot_vector, orthonormal_basis, to_world, uniform_cone


def spot_falloff(cos_angle, cos_half_size, blend):
    """Blender's spot falloff: 0 outside the cone, smoothstep over the blend region.

    ``cos_angle`` [n]: cosine between the spot axis and the direction to the lit
    point; ``blend`` in [0,1] is the fraction of (1 - cos_half_size) that fades."""
    smooth = (1.0 - cos_half_size) * blend
    if smooth <= 0.0:
        return (cos_angle > cos_half_size).astype(np.float64)
    x = np.clip((cos_angle - cos_half_size) / smooth, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


class PointLight:
    """Point (``spot`` False) or spot light; delta unless it has a radius."""

    def __init__(self, light, spectrum, spot: bool = False):
        self.name = light.name
        self.position = np.asarray(light.position, dtype=np.float64)
        self.intensity = float(light.power_w) / (4.0 * np.pi)
        self.spectrum = spectrum
        self.radius = float(max(light.radius_m, 0.0))
        self.delta = self.radius == 0.0
        self.hittable = not self.delta
        self.spot = spot
        axis = np.asarray(light.direction, dtype=np.float64)
        self.axis = axis / np.linalg.norm(axis)
        self.cos_half_size = float(np.cos(min(light.spot_size_rad, np.pi) / 2.0))
        self.blend = float(np.clip(light.spot_blend, 0.0, 1.0))
        if not self.delta:
            self.radiance = self.intensity / (np.pi * self.radius**2)

    def _falloff(self, points):
        if not self.spot:
            return np.ones(len(points))
        to_point = points - self.position
        dist = np.linalg.norm(to_point, axis=1)
        cos_a = dot_vector(to_point, self.axis) / np.where(dist > 0, dist, 1.0)
        return spot_falloff(cos_a, self.cos_half_size, self.blend)

    def sample(self, p, u, lam):
        """Direction to the light from points ``p`` [n,3]: (wi, distance, Li [n,K], pdf)."""
        to_c = self.position - p
        dist_c = np.sqrt(dot(to_c, to_c))
        safe = np.where(dist_c > 0, dist_c, 1.0)
        axis = to_c / safe[:, None]
        falloff = self._falloff(p)
        if self.delta:
            li = (self.intensity * falloff / safe**2)[:, None] * self.spectrum(lam)
            return axis, dist_c, li, np.ones(len(p))
        sin2 = np.minimum((self.radius / safe) ** 2, 1.0)
        one_minus_cos = sin2 / (1.0 + np.sqrt(1.0 - sin2))
        local = uniform_cone(u[:, :2], 1.0 - one_minus_cos)
        s, t = orthonormal_basis(axis)
        wi = to_world(local, s, t, axis)
        dist = self._hit_distance(p, wi)
        ok = (dist_c > self.radius) & np.isfinite(dist)
        pdf = np.where(ok, 1.0 / (2.0 * np.pi * np.maximum(one_minus_cos, 1e-300)), 0.0)
        li = np.where(ok, self.radiance * falloff, 0.0)[:, None] * self.spectrum(lam)
        return wi, np.where(ok, dist, 0.0), li, pdf

    def _hit_distance(self, o, d):
        oc = o - self.position
        b = dot(oc, d)
        c = dot(oc, oc) - self.radius**2
        disc = b * b - c
        root = np.sqrt(np.maximum(disc, 0.0))
        t = np.where(-b - root > 0, -b - root, -b + root)
        return np.where((disc >= 0) & (t > 0) & (c > 0), t, np.inf)

    def intersect(self, o, d):
        """Distance along rays to the sphere (inf: miss); only for soft lights."""
        return self._hit_distance(o, d)

    def emitted(self, o, d, t, lam):
        """Radiance [n,K] seen along rays that hit the sphere at ``t``."""
        return (self.radiance * self._falloff(o))[:, None] * self.spectrum(lam)

    def pdf(self, o, d, t):
        """Solid-angle density of ``sample`` for directions ``d`` from ``o`` that hit."""
        dist_c = np.linalg.norm(self.position - o, axis=1)
        sin2 = np.minimum((self.radius / np.maximum(dist_c, 1e-300)) ** 2, 1.0)
        one_minus_cos = sin2 / (1.0 + np.sqrt(1.0 - sin2))
        return 1.0 / (2.0 * np.pi * np.maximum(one_minus_cos, 1e-300))
