"""What the Light and Material panels show about a spectrum: its curve over 360-830 nm, its colour and,
for emitters, correlated colour temperature, Duv, CIE CRI Ra and ANSI/IES TM-30-18 Rf/Rg, all computed
by colour-science from the spectrum the render uses (``export.spectra`` builds it the same way).

colour-science takes a second to import, so previews are computed on one worker thread and cached by
the source's plain settings (and a file's modification time): a panel asks, gets None while the
worker runs, and redraws when ``pending()`` turns False.
"""

from __future__ import annotations

import os
import threading
import warnings
from collections import OrderedDict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from ..tracer.spectra.trapezoid import trapezoid
from ..tracer.spectra.wavelengths import VISIBLE_NM_GRID as WAVELENGTHS_NM
_FINE_PER_NM = 10
_CACHE_SIZE = 64
#: Beyond this distance from the Planckian locus, CCT and colour rendering indices mean nothing.
MAX_DUV = 0.05


@dataclass(frozen=True)
class SpectrumPreview:
    """``values`` at ``WAVELENGTHS_NM`` (emission: relative, peak 1; reflectance: 0-1), ``display_rgb``
    (emission: brightest channel 1; reflectance: its Rec.709 colour under D65), the colour metrics of
    an emitter near white (None otherwise), or ``error``: why the render would refuse it."""

    values: tuple = ()
    display_rgb: tuple = (0.0, 0.0, 0.0)
    cct_k: float | None = None
    duv: float | None = None
    cri_ra: float | None = None
    tm30_rf: float | None = None
    tm30_rg: float | None = None
    error: str | None = None


_lock = threading.Lock()
_cache: OrderedDict = OrderedDict()
_running: dict = {}
_pool: ThreadPoolExecutor | None = None


def _key(source):
    path = getattr(source, "path", "")
    stamp = os.path.getmtime(path) if path and os.path.isfile(path) else None
    return source, stamp


def _preview(compute, source, wait: bool):
    global _pool
    key = _key(source)
    with _lock:
        if key in _cache:
            _cache.move_to_end(key)
            return _cache[key]
        job = _running.get(key)
        if job is None:
            if _pool is None:
                _pool = ThreadPoolExecutor(1, thread_name_prefix="prism-spectrum-preview")
            job = _running[key] = _pool.submit(_store, compute, source, key)
    return job.result() if wait else None


def _store(compute, source, key):
    from ..tracer.errors import PrismInputError

    # colour-science notes each time it resamples its tables for an index: noise in Blender's console.
    # (A filter added once, not catch_warnings: that is not safe off the main thread.)
    warnings.filterwarnings("ignore", message='Aligning ".*', module=r"colour\.")
    try:
        preview = compute(source)
    except PrismInputError as error:
        preview = SpectrumPreview(error=str(error))
    except Exception as error:  # noqa: BLE001 - a panel shows the problem instead of failing to draw
        preview = SpectrumPreview(error=f"{type(error).__name__}: {error}")
    with _lock:
        _cache[key] = preview
        while len(_cache) > _CACHE_SIZE:
            _cache.popitem(last=False)
        _running.pop(key, None)
    return preview


def pending() -> bool:
    """True while a preview is being computed."""
    with _lock:
        return bool(_running)


def emission_preview(source, wait: bool = False) -> SpectrumPreview | None:
    """The preview of an ``export.spectra.EmissionSource`` (None while it is computed, unless ``wait``)."""
    return _preview(_emission, source, wait)


def reflectance_preview(source, wait: bool = False) -> SpectrumPreview | None:
    """The preview of an ``export.spectra.ReflectanceSource`` (None while it is computed, unless ``wait``)."""
    return _preview(_reflectance, source, wait)


def _fine_grid():
    return np.linspace(WAVELENGTHS_NM[0], WAVELENGTHS_NM[-1], (len(WAVELENGTHS_NM) - 1) * _FINE_PER_NM + 1)


def _emission(source) -> SpectrumPreview:
    from ..tracer.spectra import cie
    from ..tracer.spectra.emission_spectrum import emission_spectrum

    colour = cie.import_colour()
    spectrum = emission_spectrum(source.spec())
    fine = _fine_grid()
    values = spectrum.evaluate(fine)
    xyz = trapezoid(values[:, None] * cie.cie_xyz_cmf(fine), fine, axis=0)
    rgb = np.clip(cie.xyz_to_linear_rec709(xyz), 0.0, None)
    display = tuple(float(c) for c in rgb / rgb.max()) if rgb.max() > 0 else (0.0, 0.0, 0.0)
    # Means over each nanometre: a line narrower than a nanometre keeps its energy (plot and indices).
    area = np.concatenate([[0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(fine))])
    low, high = np.maximum(WAVELENGTHS_NM - 0.5, fine[0]), np.minimum(WAVELENGTHS_NM + 0.5, fine[-1])
    per_nm = (np.interp(high, fine, area) - np.interp(low, fine, area)) / (high - low)
    plot = per_nm / per_nm.max() if per_nm.max() > 0 else per_nm
    metrics = _light_metrics(colour, xyz, per_nm)
    return SpectrumPreview(tuple(plot.tolist()), display, **metrics)


def _light_metrics(colour, xyz, per_nm) -> dict:
    xy = xyz[:2] / xyz.sum()
    try:
        cct, duv = (float(v) for v in colour.uv_to_CCT(colour.xy_to_UCS_uv(xy), method="Ohno 2013"))
    except Exception:  # noqa: BLE001 - far from the locus colour-science may refuse: no CCT then
        return {}
    if not (np.isfinite(cct) and abs(duv) <= MAX_DUV):
        return {}
    metrics = {"cct_k": cct, "duv": duv}
    sd = colour.SpectralDistribution(dict(zip(WAVELENGTHS_NM.tolist(), per_nm.tolist())), name="Prism light")
    try:
        metrics["cri_ra"] = float(colour.colour_rendering_index(sd))
        tm30 = colour.colour_fidelity_index(sd, additional_data=True, method="ANSI/IES TM-30-18")
        metrics["tm30_rf"], metrics["tm30_rg"] = float(tm30.R_f), float(tm30.R_g)
    except Exception:  # noqa: BLE001 - the indices are extras: CCT alone is still worth showing
        pass
    return metrics


def _reflectance(source) -> SpectrumPreview:
    from ..tracer.spectra import cie
    from ..tracer.spectra.reflectance_spectrum import ReflectanceSpectrum
    from ..tracer.spectra.rgb_to_spectrum import (d65_relative_power, evaluate_sigmoid_polynomial,
                                                 reflectance_coefficients)

    spec = source.spec()
    if spec is None:
        rgb = np.asarray(source.rgb, np.float64)
        if rgb[0] == rgb[1] == rgb[2] and rgb[0] in (0.0, 1.0):
            values = np.full(len(WAVELENGTHS_NM), rgb[0])
        else:
            values = evaluate_sigmoid_polynomial(reflectance_coefficients(np.clip(rgb, 0.0, 1.0))[None],
                                                 WAVELENGTHS_NM[None])[0]
    else:
        values = ReflectanceSpectrum(spec).evaluate(WAVELENGTHS_NM)
    light = d65_relative_power(WAVELENGTHS_NM)
    cmf = cie.cie_xyz_cmf(WAVELENGTHS_NM)
    xyz = (values * light) @ cmf / (light @ cmf[:, 1])
    display = tuple(float(c) for c in np.clip(cie.xyz_to_linear_rec709(xyz), 0.0, None))
    return SpectrumPreview(tuple(np.asarray(values, np.float64).tolist()), display)
