"""Generate the GGX energy tables behind Blender's Multiscatter GGX (``engine/tracer/bsdf/multiscatter.py``).

Run once by a developer (not by Blender, not by a render):

    .venv/bin/python tools/generate_ggx_energy.py        # about fifteen minutes on one core

Energy compensation (Kulla & Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017
course; Turquin, "Practical multiple scattering compensation for microfacet models", 2019) scales a
single-scattering GGX lobe by what its single scattering misses. It needs the lobe's directional albedo
E(μ) and its cosine-weighted average E_avg = 2 ∫ E(μ) μ dμ. The tables sit on the grids Cycles reads
(``bsdf_microfacet.h``, ``microfacet_ggx_preserve_energy``), so that a lookup interpolates the same
function at the same points:

- ``ggx_e`` [32 roughness, 32 μ] and ``ggx_e_avg`` [32]: GGX reflection with F = 1. Roughness r = √alpha and
  μ = cos θ_o each uniform over 0-1 (clamped to ≥ 1e-4 at the first point).
- ``glass_e`` / ``glass_e_avg`` [16 r, 16 μ, 31 z] / [16 r, 31 z], and ``glass_inv_e`` / ``glass_inv_e_avg`` (from
  inside): a rough dielectric interface, reflection plus refraction with the exact Fresnel, counted as
  energy (no 1/η² radiance factor). z = √|(η - 1)/(η + 1)| uniform over 0-1 (clamped to 1e-4-0.99), i.e.
  η = (1 + z²)/(1 - z²) and 1/η for the inside tables; z = 0 is an index-matched interface, invisible:
  E = 1. Cycles' z grid has 16 points; ours has twice as many intervals (its points and the midpoints):
  from inside, E changes fast with η where total internal reflection sets in, and on 16 points a rough
  (r = 1) glass of index 1.5 seen from inside at normal incidence interpolates 1.3 % too bright.
- ``dielectric_fss`` [65]: the cosine-weighted average Fresnel F_avg(η) = 2 ∫ F(μ) μ dμ of a dielectric
  (η > 1) on a uniform z grid; inside (1/η) it follows by reciprocity, 1 - (1 - F_avg(η)) / η².

Albedos are integrated by deterministic quadrature: Heitz's visible-normal warp ("Sampling the GGX
Distribution of Visible Normals", JCGT 2018) maps quadrature points (``_strata``) to microfacet
normals, where the estimator G2/G1 (times F or 1 - F) is bounded and continuous; the average over μ is a
Gauss-Legendre rule. Entries agree with a brute-force integral over the hemisphere of incoming directions
to 1e-5 (``tests/tracer/bsdf/test_multiscatter_tables.py`` regenerates a few at other resolutions).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "engine" / "tracer" / "bsdf" / "data" / "ggx_energy.npz"
E_SIZE = 32  # roughness and μ points of the reflection tables (Cycles' grid)
GLASS_SIZE = 16  # roughness and μ points of the dielectric tables (Cycles' grid)
GLASS_Z = 31  # z points of the dielectric tables (Cycles' 16 and the midpoints)
FSS_SIZE = 65  # z points of the dielectric average Fresnel
STRATA = 256  # azimuth points of the visible-normal quadrature (and 1/16 of that Gauss-Legendre nodes a panel)
AVERAGE_NODES = 48  # Gauss-Legendre nodes in μ for the averages
_PANELS = (0.0, 0.125, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 13.0, 16.0, 20.0, 25.0,
           30.0, 40.0)  # Gauss-Legendre panels in x, u1 = 1 - e^-x


def grid(size: int, low: float = 1e-4, high: float = 1.0) -> np.ndarray:
    """A uniform grid over 0-1 of ``size`` points, clamped to [low, high] as the lookups' end points are."""
    return np.clip(np.linspace(0.0, 1.0, size), low, high)


def eta_of_z(z):
    """Relative index η > 1 of the parameter z = √|(η - 1)/(η + 1)|."""
    z2 = np.asarray(z, dtype=np.float64) ** 2
    return (1.0 + z2) / (1.0 - z2)


def fresnel_dielectric(cos, eta):
    """Unpolarised Fresnel reflectance for incidence cosine ``cos`` ≥ 0 into relative index ``eta``; 1 under
    total internal reflection."""
    cos = np.clip(cos, 0.0, 1.0)
    sin2_t = (1.0 - cos * cos) / (eta * eta)
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 at grazing total reflection, replaced below
        rs = (cos - eta * cos_t) / (cos + eta * cos_t)
        rp = (eta * cos - cos_t) / (eta * cos + cos_t)
    return np.where(sin2_t >= 1.0, 1.0, 0.5 * (rs * rs + rp * rp))


def _lambda(cos, alpha):
    """Smith Λ of GGX for a direction of |cosine| ``cos``."""
    cos2 = np.maximum(cos * cos, 1e-300)
    return 0.5 * (np.sqrt(1.0 + alpha * alpha * np.maximum(1.0 - cos2, 0.0) / cos2) - 1.0)


def _strata(strata: int):
    """Quadrature points (u1, u2) [S] and weights [S] over the unit square of the visible-normal warp.

    The microfacets tilted far enough to reflect below the horizon come from a sliver of u1 near 1, of
    width about alpha² (a uniform grid of 256 misses it by up to 1e-3 at roughness 0.25), so u1 = 1 - e^-x
    with a composite Gauss-Legendre rule over x in [0, 40] (panels finer where the bulk of u1 lies); u2, the
    azimuth, is a midpoint grid of ``strata`` points."""
    nodes, weights = np.polynomial.legendre.leggauss(max(strata // 16, 4))
    x, wx = [], []
    for a, b in zip(_PANELS[:-1], _PANELS[1:]):
        x.append(0.5 * (b - a) * (nodes + 1.0) + a)
        wx.append(0.5 * (b - a) * weights)
    x, wx = np.concatenate(x), np.concatenate(wx)
    i, j = np.meshgrid(np.arange(len(x)), np.arange(strata), indexing="ij")
    u1 = -np.expm1(-x)[i].ravel()
    u2 = ((j + 0.5) / strata).ravel()
    w = (np.exp(-x) * wx)[i].ravel()
    return u1, u2, w / w.sum()


def _visible_normals(mu, alpha, u1, u2):
    """Microfacet normals [M, S, 3] for views wo = (√(1-μ²), 0, μ) [M] (Heitz 2018's warp of (u1, u2) [S])."""
    sin = np.sqrt(np.maximum(1.0 - mu * mu, 0.0))
    vx, vz = alpha * sin, mu
    norm = np.sqrt(vx * vx + vz * vz)
    vx, vz = vx / norm, vz / norm  # stretched view; vy = 0, so t1 = (0, 1, 0) and t2 = v × t1 = (-vz, 0, vx)
    r = np.sqrt(u1)[None, :]
    phi = 2.0 * np.pi * u2[None, :]
    p1, p2 = r * np.cos(phi), r * np.sin(phi)
    s = 0.5 * (1.0 + vz)[:, None]
    p2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - p1 * p1)) + s * p2
    p3 = np.sqrt(np.maximum(0.0, 1.0 - p1 * p1 - p2 * p2))
    hx = -p2 * vz[:, None] + p3 * vx[:, None]
    hy = p1 + np.zeros_like(hx)
    hz = p2 * vx[:, None] + p3 * vz[:, None]
    m = np.stack([alpha * hx, alpha * hy, np.maximum(hz, 1e-12)], -1)
    return m / np.linalg.norm(m, axis=-1, keepdims=True), np.stack([sin, np.zeros_like(mu), mu], -1)


def reflection_albedo(rough: float, mu, strata: int = STRATA) -> np.ndarray:
    """E(μ) [M] of single-scattering GGX reflection with F = 1, Blender roughness ``rough`` (alpha = rough²)."""
    mu = np.atleast_1d(np.asarray(mu, dtype=np.float64))
    alpha = max(rough * rough, 1e-8)
    u1, u2, w = _strata(strata)
    m, wo = _visible_normals(mu, alpha, u1, u2)
    cos_om = np.clip(np.einsum("msk,mk->ms", m, wo), 0.0, 1.0)
    wi_z = 2.0 * cos_om * m[..., 2] - mu[:, None]
    lo = _lambda(mu, alpha)[:, None]
    weight = np.where(wi_z > 0.0, (1.0 + lo) / (1.0 + lo + _lambda(np.abs(wi_z), alpha)), 0.0)
    return weight @ w


def glass_albedo(rough: float, mu, eta: float, strata: int = STRATA) -> np.ndarray:
    """E(μ) [M] of a rough dielectric interface of relative index ``eta`` seen from the side of index 1:
    reflected plus refracted energy (Walter et al. 2007's BSDF without the 1/η² radiance factor)."""
    mu = np.atleast_1d(np.asarray(mu, dtype=np.float64))
    if abs(eta - 1.0) < 1e-6:
        return np.ones_like(mu)  # an index-matched interface is not there
    alpha = max(rough * rough, 1e-8)
    u1, u2, w = _strata(strata)
    m, wo = _visible_normals(mu, alpha, u1, u2)
    cos_om = np.clip(np.einsum("msk,mk->ms", m, wo), 0.0, 1.0)
    f = fresnel_dielectric(cos_om, eta)
    lo = _lambda(mu, alpha)[:, None]
    reflected_z = 2.0 * cos_om * m[..., 2] - mu[:, None]
    reflected = np.where(reflected_z > 0.0, (1.0 + lo) / (1.0 + lo + _lambda(np.abs(reflected_z), alpha)), 0.0)
    sin2_t = (1.0 - cos_om * cos_om) / (eta * eta)
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    # wt = -wo/η + (cos_om/η - cos_t) m; only its z matters here
    refracted_z = -mu[:, None] / eta + (cos_om / eta - cos_t) * m[..., 2]
    refracted = np.where((refracted_z < 0.0) & (sin2_t < 1.0),
                         (1.0 + lo) / (1.0 + lo + _lambda(np.abs(refracted_z), alpha)), 0.0)
    return (f * reflected + (1.0 - f) * refracted) @ w


def cosine_average(albedo, nodes: int = AVERAGE_NODES) -> float:
    """2 ∫_0^1 albedo(μ) μ dμ by Gauss-Legendre (``albedo`` takes an array of μ)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    mu = 0.5 * (x + 1.0)
    return float(np.sum(w * 0.5 * 2.0 * mu * albedo(mu)))


def dielectric_fss(eta: float) -> float:
    """F_avg(η) = 2 ∫ F(μ) μ dμ, η > 1 (no total internal reflection, so F is smooth)."""
    x, w = np.polynomial.legendre.leggauss(256)
    mu = 0.5 * (x + 1.0)
    return float(np.sum(w * mu * fresnel_dielectric(mu, eta)))


def tables(strata: int = STRATA) -> dict:
    rough_e = grid(E_SIZE)
    mu_e = grid(E_SIZE)
    ggx_e = np.stack([reflection_albedo(r, mu_e, strata) for r in rough_e])
    ggx_e_avg = np.array([cosine_average(lambda mu, r=r: reflection_albedo(r, mu, strata)) for r in rough_e])
    rough_g, mu_g, z_g = grid(GLASS_SIZE), grid(GLASS_SIZE), grid(GLASS_Z, 1e-4, 0.99)
    out = {"ggx_e": ggx_e, "ggx_e_avg": ggx_e_avg}
    for name, invert in (("glass", False), ("glass_inv", True)):
        e = np.zeros((GLASS_SIZE, GLASS_SIZE, GLASS_Z))
        e_avg = np.zeros((GLASS_SIZE, GLASS_Z))
        for c, z in enumerate(z_g):
            eta = 1.0 if c == 0 else float(eta_of_z(z))
            eta = 1.0 / eta if invert else eta
            for a, r in enumerate(rough_g):
                e[a, :, c] = glass_albedo(r, mu_g, eta, strata // 2)
                e_avg[a, c] = cosine_average(lambda mu, r=r, eta=eta: glass_albedo(r, mu, eta, strata // 4), nodes=24)
            print(f"{name}: z {c + 1}/{GLASS_Z}", flush=True)
        out[f"{name}_e"], out[f"{name}_e_avg"] = e, e_avg
    z_f = np.linspace(0.0, 1.0, FSS_SIZE)
    out["dielectric_fss"] = np.array([0.0] + [dielectric_fss(float(eta_of_z(min(z, 0.999)))) for z in z_f[1:]])
    return {key: np.clip(value, 0.0, 1.0) for key, value in out.items()}


def main():
    data = tables()
    OUTPUT.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(OUTPUT, **{key: value.astype(np.float32) for key, value in data.items()})
    print(f"wrote {OUTPUT} ({OUTPUT.stat().st_size} bytes)")


if __name__ == "__main__":
    sys.exit(main())
