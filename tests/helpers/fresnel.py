"""Fresnel equations, reflection and refraction (vectorised, float64).

Conventions: ``eta = n_transmitted / n_incident``; ``cos_theta_i`` is the cosine
between the incident ray's reversed direction and the surface normal on the
incident side. Directions are arrays [N, 3]; an incoming ``direction`` points
*toward* the surface and the ``normal`` faces the incident side (dot < 0).
Reflectances are unpolarised (mean of s and p) unless stated.

A test oracle, not shipped in the extension: the compiled Fresnel optics
(``engine/tracer/bsdf/optics.py``) are checked against it.
"""

from __future__ import annotations

import numpy as np

from engine.tracer.errors import PrismInputError


def _check_cos(cos_theta_i):
    cos_theta_i = np.asarray(cos_theta_i, dtype=np.float64)
    if not np.all(np.abs(cos_theta_i) <= 1.0 + 1e-9):
        raise PrismInputError("Fresnel: cos(theta_i) must be a finite cosine in [-1, 1] (got NaN or out of range).")
    return np.clip(cos_theta_i, -1.0, 1.0)


def _check_eta(eta, what="Fresnel"):
    eta = np.asarray(eta, dtype=np.float64)
    if not np.all((eta > 0.0) & np.isfinite(eta)):
        raise PrismInputError(f"{what}: the relative index eta = n_t / n_i must be finite and positive.")
    return eta


def fresnel_dielectric_polarized(cos_theta_i, eta):
    """(R_s, R_p) power reflectances of a dielectric interface.

    A negative ``cos_theta_i`` means the ray arrives from the transmitted side:
    the interface is flipped (eta -> 1/eta). Total internal reflection gives 1.
    """
    cos_i = _check_cos(cos_theta_i)
    eta = _check_eta(eta)
    inside = cos_i < 0.0
    eta = np.where(inside, 1.0 / eta, eta)
    cos_i = np.abs(cos_i)
    sin2_t = (1.0 - cos_i * cos_i) / (eta * eta)
    tir = sin2_t >= 1.0
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at grazing TIR, replaced below
        r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
        r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return np.where(tir, 1.0, r_s * r_s), np.where(tir, 1.0, r_p * r_p)


def fresnel_dielectric(cos_theta_i, eta):
    """Unpolarised reflectance of a dielectric interface (exact; TIR -> 1; cos < 0 flips)."""
    r_s, r_p = fresnel_dielectric_polarized(cos_theta_i, eta)
    return 0.5 * (r_s + r_p)


def reflect(direction, normal):
    """Mirror ``direction`` [..., 3] about ``normal`` [..., 3] (unit): d - 2 (d·n) n."""
    direction = np.asarray(direction, dtype=np.float64)
    normal = np.asarray(normal, dtype=np.float64)
    return direction - 2.0 * np.sum(direction * normal, axis=-1, keepdims=True) * normal


def refract(direction, normal, eta):
    """Snell refraction of unit ``direction`` [N, 3] through a surface with unit ``normal`` [N, 3].

    ``direction`` travels toward the surface, ``normal`` faces the incident side,
    ``eta = n_t / n_i`` ([N] or scalar). Returns ``(transmitted [N, 3],
    total_internal_reflection [N] bool)``; rows with TIR hold the mirror
    direction instead, so they can be used directly.
    """
    direction = np.asarray(direction, dtype=np.float64)
    normal = np.asarray(normal, dtype=np.float64)
    eta = _check_eta(eta, "refract")
    cos_i = np.clip(-np.sum(direction * normal, axis=-1), -1.0, 1.0)
    ratio = 1.0 / eta  # n_i / n_t
    sin2_t = ratio * ratio * (1.0 - cos_i * cos_i)
    tir = sin2_t > 1.0
    cos_t = np.sqrt(np.maximum(1.0 - sin2_t, 0.0))
    transmitted = ratio[..., None] * direction + (ratio * cos_i - cos_t)[..., None] * normal
    transmitted = np.where(tir[..., None], reflect(direction, normal), transmitted)
    return transmitted, tir


def fresnel_conductor_polarized(cos_theta_i, n, k, n_incident=1.0):
    """(R_s, R_p) of a conductor with complex index ``n + i k`` seen from a medium of index ``n_incident``."""
    cos_i = np.abs(_check_cos(cos_theta_i))
    n = np.asarray(n, dtype=np.float64)
    k = np.asarray(k, dtype=np.float64)
    if not (np.all(np.isfinite(n) & (n > 0.0)) and np.all(np.isfinite(k) & (k >= 0.0))):
        raise PrismInputError("Conductor Fresnel: n must be finite and > 0, k finite and >= 0.")
    eta = (n + 1j * k) / np.asarray(n_incident, dtype=np.float64)
    sin2_i = 1.0 - cos_i * cos_i
    cos_t = np.sqrt(1.0 - sin2_i / (eta * eta))  # principal branch: Re >= 0, decaying wave
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at grazing incidence on k = 0, n < 1
        r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
        r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    r_s2 = np.where(np.isfinite(r_s), np.abs(r_s) ** 2, 1.0)
    r_p2 = np.where(np.isfinite(r_p), np.abs(r_p) ** 2, 1.0)
    return r_s2, r_p2


def fresnel_conductor(cos_theta_i, n, k, n_incident=1.0):
    """Unpolarised reflectance of a conductor (exact, complex index n + i k; broadcasts).

    Real-arithmetic form of the same Fresnel equations (with a² + b² = |η² - sin²θ|,
    2a² = a² + b² + Re(η² - sin²θ)), about 1.5x faster than complex numbers on the hot path.
    """
    cos_i = np.abs(_check_cos(cos_theta_i))
    n = np.asarray(n, dtype=np.float64)
    k = np.asarray(k, dtype=np.float64)
    if not (np.all((n > 0.0) & (n < np.inf)) and np.all((k >= 0.0) & (k < np.inf))):
        raise PrismInputError("Conductor Fresnel: n must be finite and > 0, k finite and >= 0.")
    n_incident = np.asarray(n_incident, dtype=np.float64)
    eta, kappa = n / n_incident, k / n_incident
    cos2 = cos_i * cos_i
    sin2 = 1.0 - cos2
    eta2, kappa2 = eta * eta, kappa * kappa
    t0 = eta2 - kappa2 - sin2
    a2b2 = np.sqrt(t0 * t0 + 4.0 * eta2 * kappa2)
    a = np.sqrt(np.maximum(0.5 * (a2b2 + t0), 0.0))
    t1 = a2b2 + cos2
    t2 = 2.0 * cos_i * a
    t3 = cos2 * a2b2 + sin2 * sin2
    t4 = t2 * sin2
    with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 only at grazing incidence on eta = 1, k = 0
        r_s = (t1 - t2) / (t1 + t2)
        r_p = r_s * (t3 - t4) / (t3 + t4)
        r = 0.5 * (r_s + r_p)
    return np.where(np.isfinite(r), r, 1.0)
