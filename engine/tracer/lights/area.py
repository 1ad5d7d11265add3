"""Area lights: rectangle or disk (ellipse), one-sided, emitting along ``direction``.

A light of power P and area A has radiance P / (pi A) (Cycles' convention), times
its luminance-normalised spectrum. Sampled uniformly by area, converted to solid
angle; rays that hit its front face see it (its back is invisible).
"""

from __future__ import annotations

import numpy as np

from ..sampling import along, concentric_disk, dot, dot_vector


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
        su, sv = xy[:, 0] * self.half_u, xy[:, 1] * self.half_v
        wi = np.empty((len(p), 3))
        for k in range(3):  # q - p, column by column
            wi[:, k] = self.center[k] + su * self.axis_u[k] + sv * self.axis_v[k] - p[:, k]
        dist = np.sqrt(dot(wi, wi))
        safe = np.where(dist > 0, dist, 1.0)
        wi /= safe[:, None]
        cos_l = -dot_vector(wi, self.normal)
        ok = (cos_l > 0) & (dist > 0)
        pdf = np.where(ok, safe**2 / (self.area * np.where(ok, cos_l, 1.0)), 0.0)
        li = self.spectrum(lam) * self.radiance
        if not ok.all():
            li[~ok] = 0.0
        return wi, dist, li, pdf

    def intersect(self, o, d):
        """Distance to the front face along rays (inf: miss or back face)."""
        denom = dot_vector(d, self.normal)
        front = denom < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (self.center @ self.normal - dot_vector(o, self.normal)) / np.where(front, denom, -1.0)
        q = along(o - self.center, t, d)
        x = dot_vector(q, self.axis_u) / self.half_u
        y = dot_vector(q, self.axis_v) / self.half_v
        inside = (x * x + y * y <= 1.0) if self.disk else ((np.abs(x) <= 1.0) & (np.abs(y) <= 1.0))
        return np.where(front & (t > 0) & inside, t, np.inf)

    def emitted(self, o, d, t, lam):
        return self.spectrum(lam) * self.radiance

    def pdf(self, o, d, t):
        cos_l = np.abs(dot_vector(d, self.normal))
        return t * t / (self.area * np.maximum(cos_l, 1e-300))
