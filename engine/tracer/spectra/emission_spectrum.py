"""Emission spectra of lights and emissive materials, from a ``SpectrumSpec``.

Normalisation: every spectrum returned here has the luminance of RGB white,
Y = 1 in ``cie``'s normalisation (Y = ∫ S ȳ dλ / ∫ ȳ dλ), except that an ``rgb``
spectrum keeps the luminance of its colour (RGB (r, g, b) renders as (r, g, b),
like Cycles' light colour). The light's strength/power multiplies it; nothing
else does. So a blackbody's temperature changes its colour, not its brightness,
and a monochromatic line is as bright (in luminance) as a white light.

Sampling note: ``.support_nm`` gives the interval (lo, hi) outside which
``evaluate`` is exactly 0 (the visible range for all but lines); monochromatic
spectra also offer ``sample_wavelengths(u)`` / ``pdf``, proportional to the line.
The tracer's ``cie`` sampler follows the scene's emission from the spectrum table
itself (``wavelength_guide``).
"""

from __future__ import annotations

import math

import numpy as np

from . import cie
from .blackbody import blackbody_luminance, check_temperature, planck_spectral_radiance
from ..errors import PrismInputError
from .rgb_to_spectrum import RGBEmission
from .sampled import check_sampled, resample_1nm
from .tinted_blackbody import WHITE, tinted_blackbody
from .trapezoid import trapezoid
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

SPECTRUM_KINDS = ("rgb", "blackbody", "monochromatic", "illuminant", "tabulated")
_LINE_HALF_SUPPORT_FWHM = 3.0  # the Gaussian line is cut at ±3 FWHM (±7 sigma, mass lost < 1e-11)


class RGBEmissionSpectrum:
    """Linear Rec.709 colour upsampled against D65 (renders as that colour)."""

    kind = "rgb"

    def __init__(self, rgb):
        self._emission = RGBEmission(rgb)
        self.support_nm = (VISIBLE_MIN_NM, VISIBLE_MAX_NM)

    def evaluate(self, wavelength_nm):
        """Relative spectral radiance at ``wavelength_nm`` (any shape)."""
        return self._emission.evaluate(wavelength_nm)


class BlackbodyEmissionSpectrum:
    """Planck spectrum at ``temperature_k`` scaled to luminance Y = 1."""

    kind = "blackbody"

    def __init__(self, temperature_k):
        self.temperature_k = float(check_temperature(temperature_k))
        self.support_nm = (VISIBLE_MIN_NM, VISIBLE_MAX_NM)
        self._scale = 1.0 / float(blackbody_luminance(self.temperature_k))

    def evaluate(self, wavelength_nm):
        """Relative spectral radiance at ``wavelength_nm`` (any shape)."""
        return self._scale * planck_spectral_radiance(wavelength_nm, self.temperature_k)


class MonochromaticEmissionSpectrum:
    """A Gaussian line centred at ``wavelength_nm`` with full width at half maximum ``width_nm``.

    Cut to ``support_nm`` (±3 FWHM, within 360-830 nm) and scaled to Y = 1. A
    line near the ends of the visible range, where ȳ is tiny, needs a very large
    radiance to reach Y = 1: its colour is then mostly X and Z.
    """

    kind = "monochromatic"

    def __init__(self, wavelength_nm, width_nm):
        centre, width = float(wavelength_nm), float(width_nm)
        if not VISIBLE_MIN_NM <= centre <= VISIBLE_MAX_NM:
            raise PrismInputError(
                f"Monochromatic wavelength {centre:g} nm is outside {VISIBLE_MIN_NM:.0f}–{VISIBLE_MAX_NM:.0f} nm: "
                "pick a visible wavelength."
            )
        if not (math.isfinite(width) and width > 0.0):
            raise PrismInputError(
                f"Monochromatic line width {width:g} nm must be a positive number of nanometres (e.g. 10)."
            )
        self.wavelength_nm = centre
        self.width_nm = width
        self.sigma_nm = width / (2.0 * math.sqrt(2.0 * math.log(2.0)))
        half = _LINE_HALF_SUPPORT_FWHM * width
        self.support_nm = (max(VISIBLE_MIN_NM, centre - half), min(VISIBLE_MAX_NM, centre + half))
        # Integrate on a grid fine enough for the narrowest line (the 1 nm CMF grid is not).
        grid = np.linspace(self.support_nm[0], self.support_nm[1], 2001)
        luminance = trapezoid(self._shape(grid) * cie.cie_xyz_cmf(grid)[:, 1], grid) / cie.CMF_Y_INTEGRAL
        if not luminance > 0.0:
            raise PrismInputError(
                f"Monochromatic line at {centre:g} nm has no visible luminance: move it into 360–830 nm."
            )
        self._scale = 1.0 / luminance

    def _shape(self, wavelength_nm):
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        z = (wavelength_nm - self.wavelength_nm) / self.sigma_nm
        inside = (wavelength_nm >= self.support_nm[0]) & (wavelength_nm <= self.support_nm[1])
        return np.where(inside, np.exp(-0.5 * z * z), 0.0)

    def evaluate(self, wavelength_nm):
        """Relative spectral radiance at ``wavelength_nm`` (any shape); 0 outside ``support_nm``."""
        return self._scale * self._shape(wavelength_nm)

    def _cdf_bounds(self):
        from scipy.special import ndtr

        lo, hi = self.support_nm
        return ndtr((lo - self.wavelength_nm) / self.sigma_nm), ndtr((hi - self.wavelength_nm) / self.sigma_nm)

    def pdf(self, wavelength_nm):
        """Density (1/nm) of ``sample_wavelengths``: the line's shape normalised over ``support_nm``."""
        cdf_lo, cdf_hi = self._cdf_bounds()
        return self._shape(wavelength_nm) / (self.sigma_nm * math.sqrt(2.0 * math.pi) * (cdf_hi - cdf_lo))

    def sample_wavelengths(self, u):
        """Importance-sample the line: uniform ``u`` (any shape) -> ``(wavelength_nm, pdf)`` within ``support_nm``.

        Optional for the tracer: with it, ``evaluate(λ) / pdf(λ)`` is the constant luminance-normalised
        line power, so a monochromatic light renders without wavelength noise.
        """
        from scipy.special import ndtri

        u = np.asarray(u, dtype=np.float64)
        if u.size and not (np.all(u >= 0.0) and np.all(u <= 1.0)):
            raise PrismInputError("Monochromatic line sampling: uniform samples must lie in [0, 1].")
        cdf_lo, cdf_hi = self._cdf_bounds()
        p = np.clip(cdf_lo + u * (cdf_hi - cdf_lo), np.nextafter(cdf_lo, 1.0), np.nextafter(cdf_hi, 0.0))
        wavelength_nm = np.clip(self.wavelength_nm + self.sigma_nm * ndtri(p), *self.support_nm)
        return wavelength_nm, self.pdf(wavelength_nm)


class TabulatedEmissionSpectrum:
    """A measured spectrum (a standard illuminant, a spectrum file), resampled once at every nanometre
    of 360-830 nm and linearly interpolated in between, scaled to Y = 1. Beyond the data the end values
    continue, as CIE 15 recommends for missing data and colour-science does (so chromaticities match)."""

    def __init__(self, wavelength_nm, values, what, kind="tabulated"):
        self.kind = kind
        wavelength_nm, values = check_sampled(wavelength_nm, values, what)
        first_nm, values = resample_1nm(wavelength_nm, values)
        grid = np.arange(VISIBLE_MIN_NM, VISIBLE_MAX_NM + 0.5)
        self.first_nm = VISIBLE_MIN_NM
        self.values = np.interp(grid, first_nm + np.arange(len(values)), values)
        self.support_nm = (VISIBLE_MIN_NM, VISIBLE_MAX_NM)
        luminance = trapezoid(self.values * cie.cie_xyz_cmf(grid)[:, 1], grid) / cie.CMF_Y_INTEGRAL
        if not luminance > 0.0:
            raise PrismInputError(f"{what} has no visible luminance (it emits only where the eye sees nothing): "
                                  "use a spectrum that emits within 380-780 nm.")
        self._scale = 1.0 / luminance

    def evaluate(self, wavelength_nm):
        """Relative spectral radiance at ``wavelength_nm`` (any shape); 0 outside 360-830 nm."""
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        grid = self.first_nm + np.arange(len(self.values))
        inside = (wavelength_nm >= self.support_nm[0]) & (wavelength_nm <= self.support_nm[1])
        return np.where(inside, self._scale * np.interp(wavelength_nm, grid, self.values), 0.0)


class TintedBlackbodyEmissionSpectrum(TabulatedEmissionSpectrum):
    """A blackbody at ``temperature_k`` filtered by the tint ``rgb`` (not white: ``tinted_blackbody``), at every
    nanometre of 360-830 nm. Unlike a measured spectrum it is not scaled to Y = 1: a tint darkens the light as the
    colour darkens Cycles' light. The table comes ready, so nothing is resampled."""

    def __init__(self, temperature_k, rgb):  # not super().__init__: that resamples and scales to Y = 1
        self.kind = "blackbody"
        self.temperature_k = float(temperature_k)
        self.first_nm = VISIBLE_MIN_NM
        self.values = tinted_blackbody(self.temperature_k, rgb)[0]
        self.support_nm = (VISIBLE_MIN_NM, VISIBLE_MAX_NM)
        self._scale = 1.0


def emission_spectrum(spec):
    """The emission spectrum object (``.evaluate(wavelength_nm)``, ``.support_nm``) for a ``SpectrumSpec``."""
    kind = getattr(spec, "kind", None)
    if kind == "rgb":
        return RGBEmissionSpectrum(spec.rgb)
    if kind == "blackbody" and tuple(spec.rgb) != WHITE:
        check_temperature(spec.temperature_k)
        return TintedBlackbodyEmissionSpectrum(spec.temperature_k, spec.rgb)
    if kind == "blackbody":
        return BlackbodyEmissionSpectrum(spec.temperature_k)
    if kind == "monochromatic":
        return MonochromaticEmissionSpectrum(spec.wavelength_nm, spec.width_nm)
    if kind == "illuminant":
        from .illuminants import canonical_illuminant, illuminant_table

        key = canonical_illuminant(spec.illuminant)
        return TabulatedEmissionSpectrum(*illuminant_table(key), f"Illuminant {key}", kind="illuminant")
    if kind == "tabulated" and spec.table is not None:
        table = spec.table
        return TabulatedEmissionSpectrum(table.wavelength_nm, table.values, table.source or "Tabulated spectrum")
    raise PrismInputError(f"Unknown emission spectrum kind {kind!r}: use one of {', '.join(SPECTRUM_KINDS)}.")
