"""Thin-film interference: one film between two media (Airy summation, exact).

Layers: incident medium (index ``n_incident``, real) | film (``n_film``,
thickness ``thickness_nm``) | substrate (``n_substrate``; complex n + ik allowed,
e.g. a metal under a coating). A free-standing film such as a soap bubble is a
film whose substrate is the incident medium again.

With s = n_0 sin θ_0 and q_j = n_j cos θ_j = sqrt(n_j² - s²) (principal root,
so evanescent and absorbed waves decay), the interface amplitudes are

    r_ij^s = (q_i - q_j) / (q_i + q_j)                t_ij^s = 2 q_i / (q_i + q_j)
    r_ij^p = (n_j² q_i - n_i² q_j) / (n_j² q_i + n_i² q_j)   t_ij^p = 2 n_i n_j q_i / (n_j² q_i + n_i² q_j)

and the film's phase thickness is δ = 2π q_1 d / λ. Summing the multiple
reflections (Airy):

    r = (r_01 + r_12 e^{2iδ}) / (1 + r_01 r_12 e^{2iδ}),   t = t_01 t_12 e^{iδ} / (1 + r_01 r_12 e^{2iδ})

R = |r|², T_s = Re(q_2) / q_0 |t_s|², T_p = Re(q_2 n̄_2 / n_2) / q_0 |t_p|² (power
into the substrate); both polarisations are averaged (unpolarised light).

A test oracle, not shipped in the extension: the compiled thin-film optics
(``engine/tracer/bsdf/optics.py``) are checked against it.
"""

from __future__ import annotations

import numpy as np

from engine.tracer.errors import PrismInputError


def _interface(n_i, q_i, n_j, q_j):
    r_s = (q_i - q_j) / (q_i + q_j)
    t_s = 2.0 * q_i / (q_i + q_j)
    den_p = n_j * n_j * q_i + n_i * n_i * q_j
    r_p = (n_j * n_j * q_i - n_i * n_i * q_j) / den_p
    t_p = 2.0 * n_i * n_j * q_i / den_p
    return r_s, t_s, r_p, t_p


def _check(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate):
    cos_i = np.abs(np.asarray(cos_theta_i, dtype=np.float64))
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    thickness_nm = np.asarray(thickness_nm, dtype=np.float64)
    n0 = np.asarray(n_incident, dtype=np.float64)
    n1 = np.asarray(n_film, dtype=np.complex128)
    n2 = np.asarray(n_substrate, dtype=np.complex128)
    if not np.all(cos_i <= 1.0 + 1e-9):
        raise PrismInputError("Thin film: cos(theta_i) must be a finite cosine in [-1, 1].")
    if not np.all((wavelength_nm > 0.0) & (wavelength_nm < np.inf)):  # NaN fails both
        raise PrismInputError("Thin film: wavelengths must be positive, finite numbers of nm.")
    if not np.all((thickness_nm >= 0.0) & np.isfinite(thickness_nm)):
        raise PrismInputError(
            "Thin film: the film thickness must be a finite number of nanometres >= 0 (e.g. 300 for a soap film)."
        )
    if not np.all((n0 > 0.0) & np.isfinite(n0)):
        raise PrismInputError("Thin film: the incident medium's index must be finite and positive.")
    for what, n in (("film", n1), ("substrate", n2)):
        if not np.all((n.real > 0.0) & (n.real < np.inf) & (n.imag >= 0.0) & (n.imag < np.inf)):
            raise PrismInputError(
                f"Thin film: the {what} index must be finite with a positive real part and k >= 0 (e.g. 1.33)."
            )
    return np.minimum(cos_i, 1.0), wavelength_nm, thickness_nm, n0, n1, n2


def _abs2(z):
    return z.real * z.real + z.imag * z.imag


def _airy(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate, with_transmittance):
    cos_i, wavelength_nm, thickness_nm, n0, n1, n2 = _check(
        cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate
    )
    s2 = (n0 * n0) * (1.0 - cos_i * cos_i)
    n0c = n0.astype(np.complex128)
    q0 = n0c * cos_i
    # Principal roots have Re >= 0; for a real index below s (evanescent) the root is +i|.|, which decays.
    q1 = np.sqrt(n1 * n1 - s2)
    q2 = np.sqrt(n2 * n2 - s2)
    r01s, t01s, r01p, t01p = _interface(n0c, q0, n1, q1)
    r12s, t12s, r12p, t12p = _interface(n1, q1, n2, q2)
    phase = np.exp(1j * (2.0 * np.pi / wavelength_nm) * q1 * thickness_nm)
    phase2 = phase * phase
    den_s = 1.0 + r01s * r12s * phase2
    den_p = 1.0 + r01p * r12p * phase2
    grazing = cos_i == 0.0  # q0 = 0: everything is reflected
    reflectance = 0.5 * (_abs2((r01s + r12s * phase2) / den_s) + _abs2((r01p + r12p * phase2) / den_p))
    reflectance = np.clip(np.where(grazing, 1.0, reflectance), 0.0, 1.0)
    if not with_transmittance:
        return reflectance, None
    with np.errstate(invalid="ignore", divide="ignore"):
        q0_real = np.where(grazing, 1.0, np.real(q0))
        factor_s = np.real(q2) / q0_real
        factor_p = np.real(q2 * np.conj(n2) / n2) / q0_real
    t_s2 = _abs2(t01s * t12s * phase / den_s)
    t_p2 = _abs2(t01p * t12p * phase / den_p)
    transmittance = np.where(grazing, 0.0, 0.5 * (factor_s * t_s2 + factor_p * t_p2))
    return reflectance, np.clip(transmittance, 0.0, 1.0)


def thin_film_reflectance_transmittance(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate):
    """Unpolarised ``(R, T)`` of a single film; all arguments broadcast (see module docstring).

    ``cos_theta_i``: cosine of the angle of incidence in the incident medium
    (its sign is ignored). T is the power carried into the substrate (0 for a
    thick enough absorber); for non-absorbing layers R + T = 1.
    """
    return _airy(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate, True)


def thin_film_reflectance(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate):
    """Unpolarised reflectance of a single film (see ``thin_film_reflectance_transmittance``)."""
    return _airy(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate, False)[0]


def thin_film_transmittance(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate):
    """Unpolarised transmittance into the substrate (see ``thin_film_reflectance_transmittance``)."""
    return _airy(cos_theta_i, wavelength_nm, thickness_nm, n_incident, n_film, n_substrate, True)[1]
