"""The kernels' spectrum table evaluates every kind exactly as the reference physics modules do."""

import numpy as np
import pytest

from engine.tracer.scene import SpectrumSpec
from engine.tracer.spectra.conductors import conductor_nk
from engine.tracer.spectra.emission_spectrum import emission_spectrum
from engine.tracer.spectra.rgb_to_spectrum import d65_relative_power, evaluate_sigmoid_polynomial, reflectance_coefficients
from engine.tracer.spectra.table import SpectrumTable, exact_spectrum_value, spectrum_value, spectrum_values

WAVELENGTHS = np.linspace(360.0, 830.0, 97)  # on and between the dense table's nanometres
OFF_GRID = np.linspace(355.0, 835.0, 97)


def _values(arrays, sid, wavelengths=WAVELENGTHS):
    out = np.empty(len(wavelengths))
    spectrum_values(arrays, sid, wavelengths, out)
    return out


def _exact(arrays, sid, wavelengths=OFF_GRID):
    return np.array([exact_spectrum_value(arrays.kind, arrays.params, arrays.data, sid, w) for w in wavelengths])


@pytest.mark.parametrize("spec", [
    SpectrumSpec(kind="rgb", rgb=(1.0, 1.0, 1.0)),
    SpectrumSpec(kind="rgb", rgb=(3.0, 0.5, 0.1)),
    SpectrumSpec(kind="blackbody", temperature_k=3200.0),
    SpectrumSpec(kind="blackbody", temperature_k=1000.0),
    SpectrumSpec(kind="monochromatic", wavelength_nm=589.0, width_nm=2.0),
], ids=lambda s: f"{s.kind}")
def test_emission_rows_match_the_reference_spectra(spec):
    table = SpectrumTable()
    sid = table.emission(spec)
    arrays = table.arrays()
    # the exact rows, everywhere (also outside the visible range)
    assert np.allclose(_exact(arrays, sid), emission_spectrum(spec).evaluate(OFF_GRID), rtol=1e-12,
                       atol=1e-15 * emission_spectrum(spec).evaluate(OFF_GRID).max())
    # what kernels read: the dense table (lines exactly), within 2e-4 of the largest value
    expected = emission_spectrum(spec).evaluate(WAVELENGTHS)
    tolerance = 1e-12 if spec.kind == "monochromatic" else 2e-4
    assert np.allclose(_values(arrays, sid), expected, rtol=tolerance, atol=tolerance * expected.max())


def test_black_emitter_is_zero_and_rows_are_shared():
    table = SpectrumTable()
    assert table.emission(SpectrumSpec(kind="rgb", rgb=(0.0, 0.0, 0.0))) == table.emission(
        SpectrumSpec(kind="rgb", rgb=(0.0, 0.0, 0.0)))
    sid = table.emission(SpectrumSpec(kind="rgb", rgb=(0.0, 0.0, 0.0)))
    assert np.all(_values(table.arrays(), sid) == 0.0)
    a = table.reflectance((0.2, 0.5, 0.7))
    assert table.reflectance((0.2, 0.5, 0.7)) == a and len(table) == 2


@pytest.mark.parametrize("rgb", [(0.2, 0.5, 0.7), (0.9, 0.1, 0.1), (0.5, 0.5, 0.5), (1.0, 1.0, 1.0), (0.0, 0.0, 0.0)])
def test_reflectance_rows_match_the_sigmoid_polynomial(rgb):
    table = SpectrumTable()
    sid = table.reflectance(rgb)
    expected = evaluate_sigmoid_polynomial(reflectance_coefficients(np.array(rgb))[None], WAVELENGTHS[None])[0]
    assert np.allclose(_values(table.arrays(), sid), expected, rtol=0, atol=2e-4)
    whole_nm = np.arange(360.0, 831.0)
    exact = evaluate_sigmoid_polynomial(reflectance_coefficients(np.array(rgb))[None], whole_nm[None])[0]
    assert np.allclose(_values(table.arrays(), sid, whole_nm), exact, rtol=1e-13, atol=1e-15)


def test_tabulated_rows_interpolate_clamp_and_cut():
    table = SpectrumTable()
    d65 = table.d65()
    assert np.allclose(_values(table.arrays(), d65), d65_relative_power(WAVELENGTHS), rtol=1e-12)
    wl, n = np.array([400.0, 500.0, 700.0]), np.array([1.0, 2.0, 4.0])
    sid = table.resampled("test", wl, n, step_nm=1.0)
    arrays = table.arrays()
    assert np.allclose(_exact(arrays, sid, np.array([300.0, 400.0, 450.5, 600.0, 900.0])), [1.0, 1.0, 1.505, 3.0, 4.0])
    assert np.allclose(_values(arrays, sid, np.array([360.0, 450.5, 830.0])), [1.0, 1.505, 4.0])
    arrays = table.arrays()
    gold = table.resampled("Au n", *conductor_nk_table("Au"))
    arrays = table.arrays()
    assert np.allclose(_values(arrays, gold, np.array([450.0, 550.0, 650.0])),
                       conductor_nk("Au", np.array([450.0, 550.0, 650.0]))[0], rtol=2e-3)
    assert spectrum_value(arrays, sid, 500.0) == pytest.approx(2.0)


def conductor_nk_table(name):
    from engine.tracer.spectra.conductors import _lookup

    wl, n, _ = _lookup(name)
    return wl, n
