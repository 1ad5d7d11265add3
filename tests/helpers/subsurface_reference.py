"""An independent Monte Carlo of Random Walk subsurface scattering in a sphere under a white furnace, in numpy:
exact ray-sphere distances instead of Embree and a tessellated mesh, one grey channel.

A ray from a pinhole meets the sphere within ``disc`` of its image radius (uniform over the image); it refracts in
through a GGX microfacet normal drawn from the visible normals (roughness ``alpha``, index ``ior``); it flies
distances drawn from σ_t e^(−σ_t s) and scatters isotropically, each collision weighting it by the
single-scattering albedo α (d'Eon's fit of the surface albedo); the first flight that crosses the sphere is
the exit, whose Lambertian lobe of albedo 1 sees the furnace's radiance 1. Walks end after 256 steps or below
1e-6, as Cycles' and Prism's. The mean exit weight is the sphere's radiance.
"""

from __future__ import annotations

import numpy as np


def single_scattering_albedo(albedo):
    s = (4.20863 * albedo - np.sqrt(9.59217 + 41.6808 * albedo + 17.7126 * albedo ** 2) + 4.09712) ** 2
    return float(np.clip(1.0 - s, 0.0, 0.999999))


def _visible_normals(wo, alpha, u1, u2):
    v = np.stack([alpha * wo[:, 0], alpha * wo[:, 1], wo[:, 2]], 1)
    v /= np.linalg.norm(v, axis=1)[:, None]
    lensq = v[:, 0] ** 2 + v[:, 1] ** 2
    t1 = np.stack([-v[:, 1], v[:, 0], np.zeros_like(lensq)], 1) / np.sqrt(np.maximum(lensq, 1e-30))[:, None]
    t1[lensq <= 0.0] = (1.0, 0.0, 0.0)
    t2 = np.cross(v, t1)
    r, phi = np.sqrt(u1), 2.0 * np.pi * u2
    p1, p2 = r * np.cos(phi), r * np.sin(phi)
    s = 0.5 * (1.0 + v[:, 2])
    p2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - p1 ** 2)) + s * p2
    p3 = np.sqrt(np.maximum(0.0, 1.0 - p1 ** 2 - p2 ** 2))
    h = p1[:, None] * t1 + p2[:, None] * t2 + p3[:, None] * v
    h = np.stack([alpha * h[:, 0], alpha * h[:, 1], np.maximum(1e-12, h[:, 2])], 1)
    return h / np.linalg.norm(h, axis=1)[:, None]


def _camera_hits(rng, n, disc, distance):
    """Points on the unit sphere seen by a pinhole at (0, -distance, 0) through a disc of ``disc`` times the
    sphere's image radius (uniform over the image), and the directions back to the pinhole."""
    image_radius = disc / np.sqrt(distance ** 2 - 1.0)  # tan of the sphere's angular radius, times disc
    r, angle = image_radius * np.sqrt(rng.random(n)), 2.0 * np.pi * rng.random(n)
    d = np.stack([r * np.cos(angle), np.ones(n), r * np.sin(angle)], 1)
    d /= np.linalg.norm(d, axis=1)[:, None]
    origin = np.array([0.0, -distance, 0.0])
    b = d @ origin
    t = -b - np.sqrt(np.maximum(b * b - (distance ** 2 - 1.0), 0.0))
    return origin + t[:, None] * d, -d


def furnace_sphere(albedo, radius_m, alpha=1.0, ior=1.4, disc=1.0, distance=6.5, n=200_000, seed=0):
    """Mean radiance of a unit sphere of subsurface ``albedo`` and mean free path ``radius_m`` in a furnace, seen
    from ``distance`` (m) over ``disc`` of its image radius."""
    rng = np.random.default_rng(seed)
    p, wo = _camera_hits(rng, n, disc, distance)
    normal = p.copy()
    helper = np.where(np.abs(normal[:, :1]) > 0.9, [[0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0]])
    tangent = np.cross(helper, normal)
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    bitangent = np.cross(normal, tangent)
    local = np.stack([(wo * tangent).sum(1), (wo * bitangent).sum(1), (wo * normal).sum(1)], 1)
    h = _visible_normals(local, alpha, rng.random(n), rng.random(n))
    h = h[:, :1] * tangent + h[:, 1:2] * bitangent + h[:, 2:] * normal
    inverse, cos = 1.0 / ior, (wo * h).sum(1)
    d = -inverse * wo + (inverse * cos - np.sqrt(np.maximum(1.0 - inverse ** 2 * (1.0 - cos ** 2), 1e-14)))[:, None] * h
    d /= np.linalg.norm(d, axis=1)[:, None]
    alive = (d * normal).sum(1) < 0.0
    weight = alive.astype(float)
    out = np.zeros(n)
    single = single_scattering_albedo(albedo)
    for step in range(256):
        if step > 0:
            mu, phi = 2.0 * rng.random(n) - 1.0, 2.0 * np.pi * rng.random(n)
            s = np.sqrt(1.0 - mu * mu)
            d = np.where(alive[:, None], np.stack([s * np.cos(phi), s * np.sin(phi), mu], 1), d)
        t = -np.log(1.0 - rng.random(n)) * radius_m
        b, c = (p * d).sum(1), (p * p).sum(1) - 1.0
        leave = -b + np.sqrt(np.maximum(b * b - c, 0.0))
        exits = alive & (leave < t)
        out[exits] = weight[exits]
        alive &= ~exits
        p = p + np.where(alive, t, 0.0)[:, None] * d
        weight = np.where(alive, weight * single, weight)
        alive &= weight >= 1e-6
    return float(out.mean())
