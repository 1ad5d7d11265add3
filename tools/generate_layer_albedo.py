"""Generate the table of GGX reflection albedos the kernels weigh layered closures with.

Run once by a developer (not by Blender, not by a render):

    .venv/bin/python tools/generate_layer_albedo.py        # a few seconds

Blender's Principled BSDF lets its coat and specular layers take their share of the light first: the
layers below are weighted by 1 - albedo(view) of the layer above. For a single-scattering GGX reflection
whose Fresnel is the dielectric curve F(cos) remapped from [F0, 1] to [f0, 1] (Specular Tint), the albedo
is mix(f0, 1, s) · E with E the lobe's albedo for F = 1, and s = (E_F / E - F0) / (1 - F0) where E_F is
its albedo with the plain F. Blender weighs with mix(f0, 1, s) (its lobes are energy-preserving); the
table holds that s for roughness r = √alpha, view cosine μ and z = √|(η - 1) / (η + 1)|, each on a
uniform grid of 16 over [0, 1], computed here by stratified visible-normal sampling (128² samples per
entry, Heitz 2018) in numpy. Writes ``engine/tracer/materials/data/ggx_layer_albedo.npz``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "engine" / "tracer" / "materials" / "data" / "ggx_layer_albedo.npz"
SIZE = 16
STRATA = 128


def _fresnel(cos, eta):
    cos = np.clip(cos, 0.0, 1.0)
    sin2_t = (1.0 - cos * cos) / (eta * eta)
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    rs = (cos - eta * cos_t) / (cos + eta * cos_t)
    rp = (eta * cos - cos_t) / (eta * cos + cos_t)
    return np.where(sin2_t >= 1.0, 1.0, 0.5 * (rs * rs + rp * rp))


def _lambda(cos, alpha):
    cos2 = np.maximum(cos * cos, 1e-12)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * np.maximum(1.0 - cos2, 0.0) / cos2) - 1.0)


def _visible_normals(wo, alpha, u1, u2):
    v = np.array([alpha * wo[0], alpha * wo[1], wo[2]])
    v /= np.linalg.norm(v)
    lensq = v[0] ** 2 + v[1] ** 2
    t1 = np.array([-v[1], v[0], 0.0]) / np.sqrt(lensq) if lensq > 0 else np.array([1.0, 0.0, 0.0])
    t2 = np.cross(v, t1)
    r = np.sqrt(u1)
    phi = 2 * np.pi * u2
    p1, p2 = r * np.cos(phi), r * np.sin(phi)
    s = 0.5 * (1.0 + v[2])
    p2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + s * p2
    p3 = np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))
    h = p1[:, None] * t1 + p2[:, None] * t2 + p3[:, None] * v
    m = np.stack([alpha * h[:, 0], alpha * h[:, 1], np.maximum(1e-12, h[:, 2])], -1)
    return m / np.linalg.norm(m, axis=1, keepdims=True)


def table():
    grid = np.linspace(0.0, 1.0, SIZE)
    i, j = np.meshgrid(np.arange(STRATA), np.arange(STRATA), indexing="ij")
    u1 = ((i + 0.5) / STRATA).ravel()
    u2 = ((j + 0.5) / STRATA).ravel()
    out = np.zeros((SIZE, SIZE, SIZE))
    for a, rough in enumerate(grid):
        alpha = max(rough * rough, 1e-4)
        for b, mu in enumerate(grid):
            mu = max(mu, 1e-3)
            wo = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
            wm = _visible_normals(wo, alpha, u1, u2)
            cos_om = np.clip(wm @ wo, 0.0, 1.0)
            wi = 2 * cos_om[:, None] * wm - wo
            valid = wi[:, 2] > 0
            weight = np.where(valid, (1 + _lambda(wo[2], alpha)) / (1 + _lambda(wo[2], alpha)
                                                                     + _lambda(np.abs(wi[:, 2]), alpha)), 0.0)
            e1 = weight.mean()
            for c, z in enumerate(grid):
                r = min(z * z, 0.999)
                eta = (1 + r) / (1 - r)
                f0 = r * r
                e_f = (weight * _fresnel(cos_om, eta)).mean()
                out[a, b, c] = np.clip((e_f / e1 - f0) / (1 - f0), 0.0, 1.0) if e1 > 0 else 0.0
    return out


def main():
    s = table()
    OUTPUT.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(OUTPUT, dielectric_s=s.astype(np.float32))
    print(f"wrote {OUTPUT} ({OUTPUT.stat().st_size} bytes)")


if __name__ == "__main__":
    sys.exit(main())
