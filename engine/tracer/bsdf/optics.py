"""Interface optics per path, in the BSDFs' local frame (+Z = normal, directions point away).

Scalar forms of the vectorised references the tests compare against (``tests/helpers/fresnel.py``
and ``tests/helpers/thin_film.py``, which do not ship): dielectric and conductor Fresnel, Snell
refraction, and the Airy reflectance of one thin film over a substrate (complex indices allowed).
"""

from __future__ import annotations

import cmath
import math

from ..jit import kernel


@kernel
def fresnel_dielectric(cos_i, eta):
    """Unpolarised reflectance for signed ``cos_i`` (< 0: arriving from behind, so eta -> 1/eta),
    ``eta`` = index behind / index in front of the surface; 1 under total internal reflection."""
    cos_i = min(max(cos_i, -1.0), 1.0)
    if cos_i < 0.0:
        eta = 1.0 / eta
        cos_i = -cos_i
    sin2_t = (1.0 - cos_i * cos_i) / (eta * eta)
    if sin2_t >= 1.0:
        return 1.0
    cos_t = math.sqrt(max(1.0 - sin2_t, 0.0))
    r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (r_s * r_s + r_p * r_p)


@kernel
def refract(w, m, eta):
    """Refract ``w`` (pointing away) through the interface with unit normal ``m`` of the local frame's
    upper side; ``eta`` = index below / index above. Returns (wt pointing away on the other side,
    eta' = index actually entered / index left, total internal reflection)."""
    cos_i = w[0] * m[0] + w[1] * m[1] + w[2] * m[2]
    etap = eta
    nx, ny, nz = m[0], m[1], m[2]
    if cos_i < 0.0:  # arriving from below: the interface is seen the other way round
        etap = 1.0 / eta
        cos_i = -cos_i
        nx, ny, nz = -nx, -ny, -nz
    sin2_t = (1.0 - cos_i * cos_i) / (etap * etap)
    if sin2_t >= 1.0:
        return (0.0, 0.0, 0.0), etap, True
    cos_t = math.sqrt(1.0 - sin2_t)
    inv = 1.0 / etap
    return ((-w[0]) * inv + (cos_i * inv - cos_t) * nx,
            (-w[1]) * inv + (cos_i * inv - cos_t) * ny,
            (-w[2]) * inv + (cos_i * inv - cos_t) * nz), etap, False


@kernel
def fresnel_conductor(cos_i, n, k):
    """Unpolarised reflectance of a conductor of complex index n + ik seen from vacuum."""
    cos_i = min(abs(cos_i), 1.0)
    cos2 = cos_i * cos_i
    sin2 = 1.0 - cos2
    eta2 = n * n
    kappa2 = k * k
    t0 = eta2 - kappa2 - sin2
    a2b2 = math.sqrt(t0 * t0 + 4.0 * eta2 * kappa2)
    a = math.sqrt(max(0.5 * (a2b2 + t0), 0.0))
    t1 = a2b2 + cos2
    t2 = 2.0 * cos_i * a
    t3 = cos2 * a2b2 + sin2 * sin2
    t4 = t2 * sin2
    r_s = (t1 - t2) / (t1 + t2)
    r_p = r_s * (t3 - t4) / (t3 + t4)
    r = 0.5 * (r_s + r_p)
    return r if math.isfinite(r) else 1.0


@kernel
def _interface(n_i, q_i, n_j, q_j):
    r_s = (q_i - q_j) / (q_i + q_j)
    den_p = n_j * n_j * q_i + n_i * n_i * q_j
    r_p = (n_j * n_j * q_i - n_i * n_i * q_j) / den_p
    return r_s, r_p


@kernel
def thin_film_reflectance(cos_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate):
    """Airy reflectance of a film (index ``n_film``, real) of ``thickness_nm`` between a medium of real
    index ``n_incident`` and a substrate of complex index ``n_substrate``, unpolarised."""
    cos_i = min(abs(cos_i), 1.0)
    if cos_i == 0.0:
        return 1.0
    n0 = complex(n_incident, 0.0)
    n1 = complex(n_film, 0.0)
    n2 = n_substrate + 0j
    s2 = n_incident * n_incident * (1.0 - cos_i * cos_i)
    q0 = n0 * cos_i
    q1 = cmath.sqrt(n1 * n1 - s2)
    q2 = cmath.sqrt(n2 * n2 - s2)
    r01s, r01p = _interface(n0, q0, n1, q1)
    r12s, r12p = _interface(n1, q1, n2, q2)
    phase2 = cmath.exp(2j * (2.0 * math.pi / wavelength_nm) * q1 * thickness_nm)
    rs = (r01s + r12s * phase2) / (1.0 + r01s * r12s * phase2)
    rp = (r01p + r12p * phase2) / (1.0 + r01p * r12p * phase2)
    r = 0.5 * (rs.real * rs.real + rs.imag * rs.imag + rp.real * rp.real + rp.imag * rp.imag)
    return min(max(r, 0.0), 1.0)


@kernel
def dielectric_f0(eta):
    """Normal-incidence reflectance of an interface of relative index ``eta``."""
    r = (eta - 1.0) / (eta + 1.0)
    return r * r


@kernel
def tinted_fresnel(f, f0_real, tint, iridescent):
    """Blender's Specular Tint: a dielectric's reflectance ``f`` (normal-incidence value ``f0_real``) with
    F0 scaled by ``tint`` and grazing reflection kept at 1. ``f`` is remapped from [f0_real, 1] to
    [f0_real · tint, 1]; for a thin-film (``iridescent``) reflectance, which may fall below f0_real, ``f`` is
    scaled by tint as far as it is near f0_real instead. ``tint`` 1 returns ``f``."""
    if tint == 1.0:
        return f
    f0 = min(max(f0_real * tint, 0.0), 1.0)
    if iridescent:
        if f0_real <= 1e-5 or f == 1.0:
            return f
        s = min(max((f - 1.0) / (f0_real - 1.0), 0.0), 1.0)
        return f * (1.0 + (f0 / f0_real - 1.0) * s)
    if f0_real >= 1.0:
        return f
    s = min(max((f - f0_real) / (1.0 - f0_real), 0.0), 1.0)
    return f0 + (1.0 - f0) * s
