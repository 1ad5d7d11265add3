"""Wavelengths a path carries, drawn inside the kernels, and its radiance turned into RGB on the film.

Two modes (see ``wavelengths.py``, the reference implementation and test oracle):

- ``cie``: K wavelengths, the inverse-CDF images of (u + j) / K for one uniform u, from the density
  that follows the scene's emission (``wavelength_guide``, 0.1 nm cells; the visible-light density
  ∝ 1/cosh²(0.0072 (λ − 538)) on 360–830 nm when nothing emits). Column j covers the j-th of K
  equal-probability strata, so the sampler's stratification of u across a pixel's samples stratifies
  every stratum (rotating u by j/K instead, as hero-wavelength sampling usually does, keeps only the
  offsets modulo 1/K, which the sampler does not stratify). Each estimate divides by the full density
  p(λ) and the hero column is drawn uniformly, so the mixture over columns is p: unbiased whether a
  path carries all K or, after dispersion, only its hero. Radiance is integrated against the CIE 1931
  functions into XYZ, then converted to scene-linear Rec.709.
- ``gaussian_rgb``: one wavelength per R, G, B channel from that channel's truncated normal density,
  which is also the channel's response, so the channel value is radiance × response / pdf.

``WavelengthSampling`` holds everything as arrays; ``build`` makes it from the render settings.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined, kernel
from .wavelength_guide import GUIDED_CELL_NM
from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM, _TANH_HI, _TANH_LO, _VISIBLE_A_PER_NM, _VISIBLE_CENTRE_NM

MODE_CIE = 0
MODE_GAUSSIAN_RGB = 1

#: mode, count (K), guided_cdf [C+1] (empty: unguided), guided_mass [C], guided_start [4C] (the guide's
#: cut points, see ``wavelength_guide``), gaussian [3, 4] (mean nm,
#: sigma nm, cdf at 360 nm, cdf mass on 360-830 nm), cmf [471, 3] (1 nm from 360 nm),
#: xyz_to_rgb [3, 3], cmf_y_integral.
WavelengthSampling = namedtuple(
    "WavelengthSampling", "mode count guided_cdf guided_mass guided_start gaussian cmf xyz_to_rgb cmf_y_integral"
)

_VISIBLE_NORMALISATION = _TANH_HI - _TANH_LO


@kernel
def visible_pdf(wavelength_nm):
    """Density (1/nm) of the visible-light distribution; 0 outside 360-830 nm."""
    if wavelength_nm < VISIBLE_MIN_NM or wavelength_nm > VISIBLE_MAX_NM:
        return 0.0
    c = math.cosh(_VISIBLE_A_PER_NM * (wavelength_nm - _VISIBLE_CENTRE_NM))
    return _VISIBLE_A_PER_NM / (c * c * _VISIBLE_NORMALISATION)


@kernel
def sample_visible(u):
    """(wavelength_nm, pdf) from a uniform: t = tanh(a (λ - c)) is linear in u, and the density
    a / (N cosh²) = a (1 - t²) / N needs no second transcendental."""
    t = _TANH_LO + u * _VISIBLE_NORMALISATION
    lam = _VISIBLE_CENTRE_NM + 0.5 * math.log((1.0 + t) / (1.0 - t)) / _VISIBLE_A_PER_NM
    if lam < VISIBLE_MIN_NM or lam > VISIBLE_MAX_NM:
        lam = min(max(lam, VISIBLE_MIN_NM), VISIBLE_MAX_NM)
        return lam, visible_pdf(lam)
    return lam, _VISIBLE_A_PER_NM * (1.0 - t * t) / _VISIBLE_NORMALISATION


@kernel
def inverse_normal_cdf(p):
    """Φ⁻¹(p) for 0 < p < 1: Wichura's algorithm AS 241 (PPND16), relative error ~1e-16."""
    q = p - 0.5
    if abs(q) <= 0.425:
        r = 0.180625 - q * q
        num = (((((((2509.0809287301226727 * r + 33430.575583588128105) * r + 67265.770927008700853) * r
                   + 45921.953931549871457) * r + 13731.693765509461125) * r + 1971.5909503065514427) * r
                + 133.14166789178437745) * r + 3.387132872796366608)
        den = (((((((5226.495278852545925 * r + 28729.085735721942674) * r + 39307.89580009271061) * r
                   + 21213.794301586595867) * r + 5394.1960214247511077) * r + 687.1870074920579083) * r
                + 42.313330701600911252) * r + 1.0)
        return q * num / den
    r = p if q < 0.0 else 1.0 - p
    r = math.sqrt(-math.log(r))
    if r <= 5.0:
        r -= 1.6
        num = (((((((7.7454501427834140764e-4 * r + 0.0227238449892691845833) * r + 0.24178072517745061177) * r
                   + 1.27045825245236838258) * r + 3.64784832476320460504) * r + 5.7694972214606914055) * r
                + 4.6303378461565452959) * r + 1.42343711074968357734)
        den = (((((((1.05075007164441684324e-9 * r + 5.475938084995344946e-4) * r + 0.0151986665636164571966) * r
                   + 0.14810397642748007459) * r + 0.68976733498510000455) * r + 1.6763848301838038494) * r
                + 2.05319162663775882187) * r + 1.0)
    else:
        r -= 5.0
        num = (((((((2.01033439929228813265e-7 * r + 2.71155556874348757815e-5) * r + 0.0012426609473880784386) * r
                   + 0.026532189526576123093) * r + 0.29656057182850489123) * r + 1.7848265399172913358) * r
                + 5.4637849111641143699) * r + 6.6579046435011037772)
        den = (((((((2.04426310338993978564e-15 * r + 1.4215117583164458887e-7) * r + 1.8463183175100546818e-5) * r
                   + 7.868691311456132591e-4) * r + 0.0148753612908506148525) * r + 0.13692988092273580531) * r
                + 0.59983220655588793769) * r + 1.0)
    value = num / den
    return -value if q < 0.0 else value


@kernel
def gaussian_pdf(ws, channel, wavelength_nm):
    """Density (1/nm) of channel ``channel``'s truncated normal; 0 outside 360-830 nm."""
    if wavelength_nm < VISIBLE_MIN_NM or wavelength_nm > VISIBLE_MAX_NM:
        return 0.0
    g = ws.gaussian[channel]
    z = (wavelength_nm - g[0]) / g[1]
    return math.exp(-0.5 * z * z) / (math.sqrt(2.0 * math.pi) * g[1] * g[3])


@inlined
def _guided_sample(ws, u):
    cdf = ws.guided_cdf
    slots = ws.guided_start.shape[0]
    last = ws.guided_mass.shape[0] - 1
    cell = ws.guided_start[min(int(u * slots), slots - 1)]
    while cell < last and cdf[cell + 1] <= u:  # the last cell with cdf <= u
        cell += 1
    mass = ws.guided_mass[cell]
    frac = min(max((u - cdf[cell]) / mass, 0.0), 1.0) if mass > 0.0 else 0.5
    return VISIBLE_MIN_NM + (cell + frac) * GUIDED_CELL_NM, mass / GUIDED_CELL_NM


@inlined
def sample_wavelengths(ws, u0, u1, u2, wavelength_nm, pdf):
    """Fill ``wavelength_nm[K]`` and ``pdf[K]`` (1/nm) from uniforms (cie uses ``u0``; gaussian all three)."""
    count = wavelength_nm.shape[0]
    if ws.mode == MODE_GAUSSIAN_RGB:
        for c in range(3):
            u = u0 if c == 0 else (u1 if c == 1 else u2)
            g = ws.gaussian[c]
            p = g[2] + u * g[3]
            p = min(max(p, g[2] + 1e-300), g[2] + g[3] - 1e-16)
            lam = min(max(g[0] + g[1] * inverse_normal_cdf(p), VISIBLE_MIN_NM), VISIBLE_MAX_NM)
            wavelength_nm[c] = lam
            pdf[c] = gaussian_pdf(ws, c, lam)
        return
    for j in range(count):
        u = (u0 + j) / count
        if ws.guided_cdf.shape[0] > 0:
            wavelength_nm[j], pdf[j] = _guided_sample(ws, u)
        else:
            wavelength_nm[j], pdf[j] = sample_visible(u)


@kernel
def _cmf(ws, wavelength_nm, channel):
    x = wavelength_nm - VISIBLE_MIN_NM
    if not (0.0 <= x <= VISIBLE_MAX_NM - VISIBLE_MIN_NM):
        return 0.0
    i = min(int(x), ws.cmf.shape[0] - 2)
    f = x - i
    return ws.cmf[i, channel] + f * (ws.cmf[i + 1, channel] - ws.cmf[i, channel])


@kernel
def radiance_to_rgb(ws, radiance, wavelength_nm, pdf):
    """Scene-linear Rec.709 (r, g, b) of one path's spectral radiance samples."""
    count = radiance.shape[0]
    if ws.mode == MODE_GAUSSIAN_RGB:
        r = radiance[0] * gaussian_pdf(ws, 0, wavelength_nm[0]) / pdf[0] if pdf[0] > 0.0 else 0.0
        g = radiance[1] * gaussian_pdf(ws, 1, wavelength_nm[1]) / pdf[1] if pdf[1] > 0.0 else 0.0
        b = radiance[2] * gaussian_pdf(ws, 2, wavelength_nm[2]) / pdf[2] if pdf[2] > 0.0 else 0.0
        return r, g, b
    x = 0.0
    y = 0.0
    z = 0.0
    for j in range(count):
        if pdf[j] > 0.0 and radiance[j] != 0.0:
            w = radiance[j] / pdf[j]
            x += w * _cmf(ws, wavelength_nm[j], 0)
            y += w * _cmf(ws, wavelength_nm[j], 1)
            z += w * _cmf(ws, wavelength_nm[j], 2)
    norm = 1.0 / (count * ws.cmf_y_integral)
    x *= norm
    y *= norm
    z *= norm
    m = ws.xyz_to_rgb
    return (m[0, 0] * x + m[0, 1] * y + m[0, 2] * z,
            m[1, 0] * x + m[1, 1] * y + m[1, 2] * z,
            m[2, 0] * x + m[2, 1] * y + m[2, 2] * z)


def build(settings, guide=None) -> WavelengthSampling:
    """The sampling tables for ``settings`` (``RenderSettings``); ``guide``: the density that follows the
    scene's emission (``wavelength_guide.build_guide``; cie mode only, None: the visible density)."""
    from . import cie

    table_nm, cmf = cie._cmf_table()
    if table_nm[0] != VISIBLE_MIN_NM or len(table_nm) != int(VISIBLE_MAX_NM - VISIBLE_MIN_NM) + 1:
        raise RuntimeError("colour-science's CIE 1931 table is expected at 1 nm over 360-830 nm.")
    empty = np.zeros(0)
    gaussian = np.zeros((3, 4))
    if settings.wavelength_mode == "cie":
        mode, count = MODE_CIE, int(settings.wavelengths_per_path)
        guided_cdf, guided_mass, guided_start = (guide.cdf, guide.mass, guide.start) if guide is not None else (
            empty, empty, np.zeros(0, np.int32))
    else:
        from scipy.special import ndtr

        from .wavelengths import GaussianChannels

        channels = GaussianChannels(settings.channel_means_nm, settings.channel_sigmas_nm)  # validates
        mode, count = MODE_GAUSSIAN_RGB, 3
        guided_cdf, guided_mass, guided_start = empty, empty, np.zeros(0, np.int32)
        gaussian[:, 0] = channels.means_nm
        gaussian[:, 1] = channels.sigmas_nm
        gaussian[:, 2] = ndtr((VISIBLE_MIN_NM - channels.means_nm) / channels.sigmas_nm)
        gaussian[:, 3] = channels._mass
    return WavelengthSampling(mode, count, guided_cdf, guided_mass, guided_start, gaussian, np.ascontiguousarray(cmf),
                              np.ascontiguousarray(cie.XYZ_TO_LINEAR_REC709), float(cie.CMF_Y_INTEGRAL))
