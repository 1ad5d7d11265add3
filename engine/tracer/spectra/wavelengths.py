"""Wavelength sampling for the two wavelength modes.

``cie`` mode draws hero wavelengths from pbrt-v4's visible-light distribution,
``p(lambda) ∝ 1 / cosh^2(0.0072 (lambda - 538))`` on 360-830 nm, which follows
the overall shape of the colour-matching functions and has a closed-form inverse
CDF: with ``a = 0.0072 /nm`` and ``c = 538 nm`` the CDF is proportional to
``tanh(a (lambda - c))``. One uniform number u is drawn per path and column j is
the image of ``(u + j) / count``: the columns cover the ``count`` equal-probability
strata of the distribution, so the set covers the spectrum evenly and the
stratification of u across a pixel's samples carries into every stratum. Each
column is weighted by the full density; with the hero column drawn uniformly the
columns' mixture is that density, which keeps hero-wavelength termination unbiased.

``gaussian_rgb`` mode draws one wavelength per R, G, B channel from that
channel's normal distribution truncated to 360-830 nm (the truncation is in the
pdf, so the estimator stays unbiased).

All wavelengths are in nanometres (float64).
"""

from __future__ import annotations

import numpy as np

from ..errors import PrismInputError

# The visible range every path's wavelengths lie in (the CIE 1931 tables' extent): the one home of
# 360-830 nm for the tracer, the export, the properties, the panels, the tools and the benchmarks.
VISIBLE_MIN_NM = 360.0
VISIBLE_MAX_NM = 830.0
VISIBLE_RANGE_NM = (VISIBLE_MIN_NM, VISIBLE_MAX_NM)
#: Every whole nanometre of the visible range (471 values): the grid of the dense spectrum tables,
#: the previews and the spectral colour fits. Left writable (never written): numba compiles a
#: separate specialisation for read-only arrays, and this grid reaches kernels.
VISIBLE_NM_GRID = np.arange(VISIBLE_MIN_NM, VISIBLE_MAX_NM + 1.0)

_VISIBLE_A_PER_NM = 0.0072
_VISIBLE_CENTRE_NM = 538.0
_TANH_LO = np.tanh(_VISIBLE_A_PER_NM * (VISIBLE_MIN_NM - _VISIBLE_CENTRE_NM))
_TANH_HI = np.tanh(_VISIBLE_A_PER_NM * (VISIBLE_MAX_NM - _VISIBLE_CENTRE_NM))
_VISIBLE_NORMALISATION = _TANH_HI - _TANH_LO  # integral of a/cosh^2 over the range


def visible_wavelength_pdf(wavelength_nm):
    """Density (1/nm) of the visible-light wavelength distribution.

    ``0.0072 / cosh^2(0.0072 (lambda - 538))`` normalised over 360-830 nm; zero
    outside that range (and for NaN).
    """
    wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
    inside = (wavelength_nm >= VISIBLE_MIN_NM) & (wavelength_nm <= VISIBLE_MAX_NM)
    x = _VISIBLE_A_PER_NM * (wavelength_nm - _VISIBLE_CENTRE_NM)
    density = _VISIBLE_A_PER_NM / (np.cosh(x) ** 2 * _VISIBLE_NORMALISATION)
    return np.where(inside, density, 0.0)


def _visible_inverse_cdf(u):
    x = np.arctanh(_TANH_LO + u * _VISIBLE_NORMALISATION)
    wavelength_nm = _VISIBLE_CENTRE_NM + x / _VISIBLE_A_PER_NM
    return np.clip(wavelength_nm, VISIBLE_MIN_NM, VISIBLE_MAX_NM)


def _check_uniform(u, name):
    u = np.asarray(u, dtype=np.float64)
    if u.size and not (np.all(u >= 0.0) and np.all(u <= 1.0)):
        raise PrismInputError(f"{name}: uniform samples must lie in [0, 1] and not be NaN.")
    return u


def sample_visible_wavelengths(u, count):
    """Stratified hero-wavelength sampling of the visible range.

    ``u``: uniform samples in [0, 1), shape [N]. ``count``: wavelengths per path.
    Returns ``(wavelength_nm [N, count], pdf [N, count])``: column j lies in the
    j-th of ``count`` equal-probability strata; ``pdf`` is the full density
    ``visible_wavelength_pdf`` at each wavelength (the estimators divide by it).
    """
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise PrismInputError(f"Wavelengths per path must be a positive integer (got {count!r}).")
    u = _check_uniform(u, "sample_visible_wavelengths").reshape(-1)
    strata = (u[:, None] + np.arange(count, dtype=np.float64)[None, :]) / count
    wavelength_nm = _visible_inverse_cdf(strata)
    return wavelength_nm, visible_wavelength_pdf(wavelength_nm)


class GaussianChannels:
    """The ``gaussian_rgb`` mode's three channel distributions (R, G, B).

    Each channel is a normal distribution (``means_nm``, ``sigmas_nm``) truncated
    to 360-830 nm. Its density is also the channel's spectral response, so the
    RGB estimate is ``L(lambda) * response / pdf``.
    """

    def __init__(self, means_nm=(600.0, 550.0, 450.0), sigmas_nm=(25.0, 25.0, 15.0)):
        means = np.asarray(means_nm, dtype=np.float64).reshape(-1)
        sigmas = np.asarray(sigmas_nm, dtype=np.float64).reshape(-1)
        if means.shape != (3,) or sigmas.shape != (3,):
            raise PrismInputError("Gaussian channels need three means and three sigmas (R, G, B), in nm.")
        for channel, mean, sigma in zip("RGB", means, sigmas):
            if not VISIBLE_MIN_NM <= mean <= VISIBLE_MAX_NM:
                raise PrismInputError(
                    f"The {channel} channel's mean wavelength {mean} nm is outside "
                    f"{VISIBLE_MIN_NM:.0f}-{VISIBLE_MAX_NM:.0f} nm: pick a visible wavelength."
                )
            if not (np.isfinite(sigma) and sigma > 0.0):
                raise PrismInputError(f"The {channel} channel's sigma must be positive (got {sigma} nm).")
        from scipy.special import ndtr

        self.means_nm = means
        self.sigmas_nm = sigmas
        self._cdf_lo = ndtr((VISIBLE_MIN_NM - means) / sigmas)
        self._cdf_hi = ndtr((VISIBLE_MAX_NM - means) / sigmas)
        self._mass = self._cdf_hi - self._cdf_lo

    def __repr__(self):
        return f"GaussianChannels(means_nm={tuple(self.means_nm)}, sigmas_nm={tuple(self.sigmas_nm)})"

    def sample(self, u):
        """Draw one wavelength per channel.

        ``u``: uniform samples [N, 3] (column c feeds channel c). Returns
        ``(wavelength_nm [N, 3], pdf [N, 3])``.
        """
        from scipy.special import ndtri

        u = _check_uniform(u, "GaussianChannels.sample")
        if u.ndim != 2 or u.shape[1] != 3:
            raise PrismInputError(f"GaussianChannels.sample needs uniform samples of shape [N, 3] (got {u.shape}).")
        p = self._cdf_lo + u * self._mass
        p = np.clip(p, np.nextafter(self._cdf_lo, 1.0), np.nextafter(self._cdf_hi, 0.0))
        wavelength_nm = np.clip(self.means_nm + self.sigmas_nm * ndtri(p), VISIBLE_MIN_NM, VISIBLE_MAX_NM)
        return wavelength_nm, self.pdf(wavelength_nm)

    def pdf(self, wavelength_nm):
        """Density (1/nm) of each channel at ``wavelength_nm [..., 3]``; zero outside 360-830 nm."""
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        z = (wavelength_nm - self.means_nm) / self.sigmas_nm
        density = np.exp(-0.5 * z * z) / (np.sqrt(2.0 * np.pi) * self.sigmas_nm * self._mass)
        inside = (wavelength_nm >= VISIBLE_MIN_NM) & (wavelength_nm <= VISIBLE_MAX_NM)
        return np.where(inside, density, 0.0)
