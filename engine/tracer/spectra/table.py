"""Every spectrum a render uses, as one flat table the kernels evaluate per wavelength.

A spectrum is a row: an integer kind and ``SPECTRUM_ROW`` float64 parameters, plus, for tabulated
spectra, a run of values in a shared data array. Materials and lights refer to spectra by row id.

Kinds and parameters (λ in nm):

- ``CONSTANT``: p0 at every wavelength.
- ``SIGMOID``: Jakob-Hanika reflectance S(λ) = 1/2 + U / (2 sqrt(1 + U²)), U = p0 λ² + p1 λ + p2, in [0, 1].
- ``RGB_ILLUMINANT``: p3 · S(λ; p0, p1, p2) · D65(λ), the D65 spectrum being the tabulated row p4
  (``rgb_to_spectrum.RGBEmission``: an RGB emitter's spectrum).
- ``BLACKBODY``: p1 · Planck(λ, T = p0), W·sr⁻¹·m⁻²·nm⁻¹ scaled to a luminance.
- ``LINE``: p4 · exp(-(λ - p0)² / (2 p1²)) on [p2, p3], zero outside (a monochromatic emission line).
- ``TABULATED``: linear interpolation of ``data[p0 : p0 + p1]`` sampled at p2 + i p3 nm, times p4; the
  end values continue beyond the table; zero outside [p5, p6].

Kernels read every kind but ``LINE`` from a dense table: each spectrum evaluated exactly once per render
at every nanometre of 360-830 nm and interpolated linearly in between (pbrt-v4 keeps densely sampled
spectra at 1 nm too). A sigmoid or blackbody differs from its interpolant by < 2e-4 (absolute for reflectances, relative for emission) over
the visible range (a 1000 K blackbody at 360 nm, where it is 1e-10 of its peak, is the extreme); lines
(2 nm wide and less) are evaluated exactly.

The Python side (``SpectrumTable``) builds rows from the physics modules of this package (which stay the
reference and the test oracle) and never evaluates spectra per ray.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..jit import inlined, kernel
from .wavelengths import VISIBLE_MIN_NM, VISIBLE_NM_GRID

CONSTANT = 0
SIGMOID = 1
RGB_ILLUMINANT = 2
BLACKBODY = 3
LINE = 4
TABULATED = 5

SPECTRUM_ROW = 8

DENSE_START_NM = VISIBLE_MIN_NM
DENSE_COUNT = len(VISIBLE_NM_GRID)  # every nanometre of 360-830 nm

#: The kernels' view of a ``SpectrumTable``: kind int32 [S], params float64 [S, SPECTRUM_ROW], data
#: float64 [D], dense float64 [S, DENSE_COUNT] (each spectrum at 360, 361, ... 830 nm).
SpectrumArrays = namedtuple("SpectrumArrays", "kind params data dense")

# Planck's law constants (see blackbody.py, CODATA 2018): c1 = 2hc², c2 = hc/k, λ in m.
_PLANCK_C1 = 2.0 * 6.62607015e-34 * 299792458.0**2
_PLANCK_C2 = 6.62607015e-34 * 299792458.0 / 1.380649e-23
_MAX_EXPONENT = 700.0


@kernel
def sigmoid_polynomial(c0, c1, c2, wavelength_nm):
    """Jakob-Hanika reflectance at ``wavelength_nm`` (0 and 1 exactly for c2 = -inf / +inf)."""
    u = (c0 * wavelength_nm + c1) * wavelength_nm + c2
    if u > 1e10:
        u = 1e10
    elif u < -1e10:
        u = -1e10
    return 0.5 + 0.5 * u / math.sqrt(1.0 + u * u)


@kernel
def _tabulated(params, data, wavelength_nm):
    if not (params[5] <= wavelength_nm <= params[6]):
        return 0.0
    count = int(params[1])
    x = (wavelength_nm - params[2]) / params[3]
    if x <= 0.0:
        return params[4] * data[int(params[0])]
    if x >= count - 1:
        return params[4] * data[int(params[0]) + count - 1]
    i = int(x)
    f = x - i
    base = int(params[0]) + i
    return params[4] * (data[base] + f * (data[base + 1] - data[base]))


@kernel
def planck(wavelength_nm, temperature_k):
    """Blackbody spectral radiance, W·sr⁻¹·m⁻²·nm⁻¹ (0 where the exponent would overflow)."""
    wavelength_m = wavelength_nm * 1e-9
    exponent = _PLANCK_C2 / (wavelength_m * temperature_k)
    if exponent > _MAX_EXPONENT:
        return 0.0
    return _PLANCK_C1 / (wavelength_m**5 * math.expm1(exponent)) * 1e-9


@kernel
def exact_spectrum_value(kind, params, data, sid, wavelength_nm):
    """Value of spectrum row ``sid`` (kinds ``kind`` [S], ``params`` [S, SPECTRUM_ROW], ``data``)."""
    k = kind[sid]
    p = params[sid]
    if k == CONSTANT:
        return p[0]
    if k == SIGMOID:
        return sigmoid_polynomial(p[0], p[1], p[2], wavelength_nm)
    if k == RGB_ILLUMINANT:
        d65 = _tabulated(params[int(p[4])], data, wavelength_nm)
        return p[3] * sigmoid_polynomial(p[0], p[1], p[2], wavelength_nm) * d65
    if k == BLACKBODY:
        return p[1] * planck(wavelength_nm, p[0])
    if k == LINE:
        if wavelength_nm < p[2] or wavelength_nm > p[3]:
            return 0.0
        z = (wavelength_nm - p[0]) / p[1]
        return p[4] * math.exp(-0.5 * z * z)
    if k == TABULATED:
        return _tabulated(p, data, wavelength_nm)
    return 0.0


@kernel
def _tabulate(kind, params, data, dense):
    for sid in range(kind.shape[0]):
        for i in range(dense.shape[1]):
            dense[sid, i] = exact_spectrum_value(kind, params, data, sid, DENSE_START_NM + i)


@kernel
def spectrum_value(spectra, sid, wavelength_nm):
    """Value of spectrum row ``sid`` of ``spectra`` (a ``SpectrumArrays``) at ``wavelength_nm``
    (360-830 nm: the wavelengths paths carry)."""
    if spectra.kind[sid] == LINE:
        return exact_spectrum_value(spectra.kind, spectra.params, spectra.data, sid, wavelength_nm)
    x = min(max(wavelength_nm - DENSE_START_NM, 0.0), DENSE_COUNT - 1.0)
    i = min(int(x), DENSE_COUNT - 2)
    row = spectra.dense[sid]
    return row[i] + (x - i) * (row[i + 1] - row[i])


@inlined
def spectrum_values(spectra, sid, wavelengths_nm, out):
    """``out[k]`` = spectrum ``sid`` at ``wavelengths_nm[k]`` for every carried wavelength."""
    for k in range(wavelengths_nm.shape[0]):
        out[k] = spectrum_value(spectra, sid, wavelengths_nm[k])


class SpectrumTable:
    """Builds the rows; identical requests share a row. ``arrays()`` gives the kernels' view."""

    def __init__(self):
        self._kinds: list[int] = []
        self._params: list[np.ndarray] = []
        self._data: list[float] = []
        self._rows: dict = {}

    def __len__(self) -> int:
        return len(self._kinds)

    def _row(self, key, kind, params) -> int:
        if key in self._rows:
            return self._rows[key]
        row = np.zeros(SPECTRUM_ROW)
        row[: len(params)] = params
        self._kinds.append(kind)
        self._params.append(row)
        self._rows[key] = len(self._kinds) - 1
        return self._rows[key]

    def constant(self, value: float) -> int:
        return self._row(("constant", float(value)), CONSTANT, [float(value)])

    def reflectance(self, rgb) -> int:
        """A reflectance (values 0-1) upsampled from a linear Rec.709 colour."""
        from .rgb_to_spectrum import reflectance_coefficients

        rgb = tuple(float(c) for c in rgb)
        if rgb[0] == rgb[1] == rgb[2] and rgb[0] in (0.0, 1.0):
            return self.constant(rgb[0])  # the sigmoid only approaches 0 and 1
        key = ("reflectance", rgb)
        if key not in self._rows:
            c = reflectance_coefficients(np.asarray(rgb))
            return self._row(key, SIGMOID, list(c))
        return self._rows[key]

    def measured_reflectance(self, spec, what="Reflectance") -> int:
        """A measured reflectance (0-1) for a ``scene.ReflectanceSpec`` (colour-checker patch or file);
        ``what`` names its owner in messages."""
        from .reflectance_spectrum import ReflectanceSpectrum

        key = ("measured reflectance", spec)
        if key not in self._rows:
            source = ReflectanceSpectrum(spec, what)
            self._rows[key] = self.tabulated(key, source.first_nm, 1.0, source.values)
        return self._rows[key]

    def tabulated(self, key, start_nm: float, step_nm: float, values, scale=1.0, support_nm=(-math.inf, math.inf)) -> int:
        """Values sampled every ``step_nm`` from ``start_nm`` (identified by ``key`` for sharing)."""
        full_key = ("tabulated", key, float(scale))
        if full_key in self._rows:
            return self._rows[full_key]
        values = np.asarray(values, dtype=np.float64)
        offset = len(self._data)
        self._data.extend(values.tolist())
        return self._row(full_key, TABULATED,
                         [offset, len(values), start_nm, step_nm, scale, support_nm[0], support_nm[1]])

    def resampled(self, key, wavelength_nm, values, step_nm=1.0) -> int:
        """Irregularly sampled values (e.g. measured n, k), resampled once on a uniform grid."""
        wavelength_nm = np.asarray(wavelength_nm, dtype=np.float64)
        grid = np.arange(wavelength_nm[0], wavelength_nm[-1] + 0.5 * step_nm, step_nm)
        return self.tabulated(key, float(grid[0]), step_nm, np.interp(grid, wavelength_nm, values))

    def d65(self) -> int:
        """CIE D65 relative power (100 at 560 nm), zero outside 360-830 nm."""
        from .rgb_to_spectrum import _d65_table
        from .wavelengths import VISIBLE_MAX_NM, VISIBLE_MIN_NM

        table_nm, power = _d65_table()
        return self.tabulated("D65", float(table_nm[0]), float(table_nm[1] - table_nm[0]), power,
                              support_nm=(VISIBLE_MIN_NM, VISIBLE_MAX_NM))

    def emission(self, spec) -> int:
        """A luminance-normalised emission spectrum for a ``scene.SpectrumSpec`` (radiance per unit strength)."""
        from .emission_spectrum import BlackbodyEmissionSpectrum, TabulatedEmissionSpectrum, emission_spectrum

        key = ("emission", spec)
        if key in self._rows:
            return self._rows[key]
        source = emission_spectrum(spec)
        if spec.kind == "rgb":
            emission = source._emission
            if emission.scale == 0.0:
                return self._row(key, CONSTANT, [0.0])
            c = emission.coefficients
            return self._row(key, RGB_ILLUMINANT,
                             [c[0], c[1], c[2], emission.scale / emission._d65_norm, self.d65()])
        if isinstance(source, BlackbodyEmissionSpectrum):  # Planck's law evaluated in the kernels
            return self._row(key, BLACKBODY, [source.temperature_k, source._scale])
        if isinstance(source, TabulatedEmissionSpectrum):  # every nanometre (illuminants, files, tinted blackbodies)
            sid = self.tabulated(key, source.first_nm, 1.0, source.values, source._scale, source.support_nm)
            self._rows[key] = sid
            return sid
        lo, hi = source.support_nm
        return self._row(key, LINE, [source.wavelength_nm, source.sigma_nm, lo, hi, source._scale])

    def arrays(self) -> SpectrumArrays:
        """The kernels' view (a snapshot: rows added later need a new call)."""
        kind = np.array(self._kinds, dtype=np.int32)
        params = np.array(self._params, dtype=np.float64).reshape(-1, SPECTRUM_ROW)
        data = np.array(self._data if self._data else [0.0], dtype=np.float64)
        dense = np.zeros((len(kind), DENSE_COUNT))
        _tabulate(kind, params, data, dense)
        return SpectrumArrays(kind, params, data, dense)
