"""Interface optics in the BSDFs' conventions, as thin adapters over the physics
modules (``fresnel``, ``thin_film``, ``conductors``).

BSDF conventions: directions point away from the surface; ``eta`` = index behind
the surface / index in front (front = the +normal side). Inputs are sanitised
(cosines clipped, NaN zeroed) so one degenerate path cannot abort a render; the
integrator drops the path instead.
"""

from __future__ import annotations

import numpy as np

from ..sampling import dot

from ..spectra import fresnel as _fresnel


def _cos(c):
    return np.clip(np.nan_to_num(np.asarray(c, dtype=np.float64)), -1.0, 1.0)


def fresnel_dielectric(cos_i: np.ndarray, eta: np.ndarray) -> np.ndarray:
    """Unpolarised reflectance [n] for signed ``cos_i`` (< 0: arriving from behind,
    the index ratio is inverted); 1 under total internal reflection."""
    return _fresnel.fresnel_dielectric(_cos(cos_i), eta)


def refract(w: np.ndarray, n: np.ndarray, eta: np.ndarray):
    """Refract ``w`` [n,3] (pointing away) through the interface with normal ``n``.

    Returns (transmitted direction [n,3] (pointing away on the other side),
    eta' [n] = relative index actually crossed (n_t / n_i), tir [n] bool)."""
    eta = np.broadcast_to(np.asarray(eta, dtype=np.float64), (len(w),))
    inside = dot(w, n) < 0
    etap = np.where(inside, 1.0 / eta, eta)
    facing = np.where(inside[:, None], -n, n)
    t, tir = _fresnel.refract(-np.nan_to_num(w), facing, etap)
    return t, etap, tir


def conductor_fresnel(cos_i: np.ndarray, name: str, lam: np.ndarray) -> np.ndarray:
    """Reflectance [n,K] of a named metal (measured n, k) at ``cos_i`` [n]."""
    from ..path_spectra import conductor_nk

    n, k = conductor_nk(name, lam)
    return _fresnel.fresnel_conductor(np.abs(_cos(cos_i))[:, None], n, k)


def coating_reflectance(thickness_nm: float, coating_ior: float):
    """R(cos_i [n], n_incident [n], n_substrate [n], lam [n,K]) -> [n,K] of a film on a dielectric."""
    from ..spectra.thin_film import thin_film_reflectance

    def reflectance(cos_i, n_incident, n_substrate, lam):
        return thin_film_reflectance(np.abs(_cos(cos_i))[:, None], lam, thickness_nm, n_incident[:, None],
                                     coating_ior, n_substrate[:, None])

    return reflectance


def coated_conductor_fresnel(material, spectra):
    """F(cos_i [n], lam [n,K]) of a thin film of index ``coating_ior`` over a metal: the
    named metal's n + ik, or (base colour only) the real index with that normal reflectance."""
    from ..path_spectra import conductor_nk
    from ..spectra.thin_film import thin_film_reflectance

    d, n_film = float(material.coating_thickness_nm), float(material.coating_ior)
    f0 = None if material.conductor else spectra.reflectance(material.base_color)

    def fresnel(cos_i, lam):
        if f0 is None:
            n, k = conductor_nk(material.conductor, lam)
            index = n + 1j * k
        else:
            r = np.sqrt(np.clip(f0(lam), 0.0, 0.999))
            index = (1.0 + r) / (1.0 - r)
        return thin_film_reflectance(np.abs(_cos(cos_i))[:, None], lam, d, 1.0, n_film, index)

    return fresnel


def free_film_reflectance(thickness_nm: float, film_ior: float):
    """R(cos_i [n], lam [n,K]) -> [n,K] of a free-standing film in air."""
    from ..spectra.thin_film import thin_film_reflectance

    def reflectance(cos_i, lam):
        return thin_film_reflectance(np.abs(_cos(cos_i))[:, None], lam, thickness_nm, 1.0, film_ior, 1.0)

    return reflectance
