"""Interface optics in the BSDFs' conventions (directions point away from the surface;
``eta`` = index behind the surface / index in front, where "front" is +n).

Thin adapters over the physics module ``fresnel`` when it is available.
"""

from __future__ import annotations

import numpy as np


def fresnel_dielectric(cos_i: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Unpolarised reflectance [n] for signed ``cos_i`` (< 0: arriving from behind,
    the index ratio is inverted); 1 under total internal reflection."""
    cos_i = np.asarray(cos_i, dtype=np.float64)
    eta = np.broadcast_to(np.asarray(eta, dtype=np.float64), cos_i.shape)
    inside = cos_i < 0
    eta = np.where(inside, 1.0 / eta, eta)
    c = np.clip(np.abs(cos_i), 0.0, 1.0)
    sin2_t = (1.0 - c * c) / (eta * eta)
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin2_t))
    with np.errstate(divide="ignore", invalid="ignore"):
        r_par = (eta * c - cos_t) / (eta * c + cos_t)
        r_perp = (c - eta * cos_t) / (c + eta * cos_t)
    r = 0.5 * (r_par * r_par + r_perp * r_perp)
    return np.where(sin2_t >= 1.0, 1.0, np.where(np.isfinite(r), r, 1.0))


def refract(w: np.ndarray, n: np.ndarray, eta: np.ndarray):
    """Refract ``w`` [n,3] (pointing away) through the interface with normal ``n``.

    Returns (transmitted direction [n,3] (pointing away on the other side),
    eta' [n] = relative index actually crossed (n_t / n_i), tir [n] bool)."""
    cos_i = (w * n).sum(1)
    inside = cos_i < 0
    eta = np.where(inside, 1.0 / eta, eta)
    nn = np.where(inside[:, None], -n, n)
    cos_i = np.abs(cos_i)
    sin2_t = np.maximum(0.0, 1.0 - cos_i * cos_i) / (eta * eta)
    tir = sin2_t >= 1.0
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin2_t))
    wt = -w / eta[:, None] + (cos_i / eta - cos_t)[:, None] * nn
    return wt, eta, tir
