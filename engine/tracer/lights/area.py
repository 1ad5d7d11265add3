"""Area lights: rectangle or disk (ellipse), one-sided, emitting along ``direction``.

A light of power P and area A has radiance P / (pi A) (Cycles' convention), times
its luminance-normalised spectrum. Sampled uniformly by area, converted to solid
angle; rays that hit its front face see it (its back is invisible).
"""

from __future__ import annotations

import numpy as np

from ..sampling import concentric_disk, dot


class AreaLight:
    delta = False
    hittable = True

    def __init__(self, light, spectrum):
        self.name = light.name
        self.center = np.asarray(light.position, dtype=np.float64)
        n = np.asarray(light.direction, dtype=np.float64)
        self.normal = n / np.linalg.norm(n)
        u = np.asarray(light.axis_u, dtype=np.float64)
        u = u - self.normal * (u @ self.normal)
        self.axis_u = u / np.linalg.norm(u)
        self.axis_v = np.cross(self.normal, self.axis_u)
        if np.asarray(light.axis_v) @ self.axis_v < 0:
            self.axis_v = -self.axis_v
        self.half_u = 0.5 * float(light.size_u_m)
        self.half_v = 0.5 * float(light.size_v_m)
        self.disk = light.area_shape == "disk"
        self.area = (np.pi if self.disk else 4.0) * self.half_u * self.half_v
        self.radiance = float(light.power_w) / (np.pi * self.area) if self.area > 0 else 0.0
        self.spectrum = spectrum

    def sample(self, p, u, lam):
        """Uniform point on the light seen from ``p`` [n,3]: (wi, distance, Li [n,K], pdf)."""
        if self.disk:
            xy = concentric_disk(u[:, :2])
        else:
            xy = 2.0 * u[:, :2] - 1.0
        q = self.center + (xy[:, 0:1] * self.half_u) * self.axis_u + (xy[:, 1:2] * self.half_v) * self.axis_v
        wi = q - p
        dist = np.sqrt(dot(wi, wi))
        safe = np.where(dist > 0, dist, 1.0)
        wi = wi / safe[:, None]
        cos_l = -(wi @ self.normal)
        ok = (cos_l > 0) & (dist > 0)
        pdf = np.where(ok, safe**2 / (self.area * np.where(ok, cos_l, 1.0)), 0.0)
        li = np.where(ok, self.radiance, 0.0)[:, None] * self.spectrum(lam)
        return wi, dist, li, pdf

    def intersect(self, o, d):
        """Distance to the front face along rays (inf: miss or back face)."""
        denom = d @ self.normal
        front = denom < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = ((self.center - o) @ self.normal) / np.where(front, denom, -1.0)
        q = o + t[:, None] * d - self.center
        x = (q @ self.axis_u) / self.half_u
        y = (q @ self.axis_v) / self.half_v
        inside = (x * x + y * y <= 1.0) if self.disk else ((np.abs(x) <= 1.0) & (np.abs(y) <= 1.0))
        return np.where(front & (t > 0) & inside, t, np.inf)

    def emitted(self, o, d, t, lam):
        return np.full(len(o), self.radiance)[:, None] * self.spectrum(lam)

    def pdf(self, o, d, t):
        cos_l = np.abs(d @ self.normal)
        return t * t / (self.area * np.maximum(cos_l, 1e-300))
