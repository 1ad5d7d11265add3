"""Measured spectra are checked once (one message naming the spectrum and the fix) and resampled
once at every nanometre: exactly at coarse data points, keeping the energy of fine data."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.spectra.sampled import check_sampled, resample_1nm
from engine.tracer.spectra.trapezoid import trapezoid


def test_coarse_data_is_interpolated_and_exact_at_its_points():
    wavelength_nm = np.arange(380.0, 781.0, 5.0)
    values = np.random.default_rng(0).random(len(wavelength_nm))
    first, resampled = resample_1nm(*check_sampled(wavelength_nm, values, "x"))
    assert first == 380.0 and len(resampled) == 401
    assert np.allclose(resampled[::5], values)


def test_fine_data_keeps_the_energy_of_a_line_narrower_than_a_nanometre():
    wavelength_nm = np.arange(500.0, 620.0, 0.05)
    values = np.exp(-0.5 * ((wavelength_nm - 589.37) / 0.1) ** 2)
    first, resampled = resample_1nm(wavelength_nm, values)
    assert resampled.sum() == pytest.approx(trapezoid(values, wavelength_nm), rel=1e-6)
    assert first + np.argmax(resampled) == 589.0


def test_unsorted_rows_are_sorted():
    wavelength_nm, values = check_sampled([500.0, 400.0, 600.0], [2.0, 1.0, 3.0], "x")
    assert wavelength_nm.tolist() == [400.0, 500.0, 600.0] and values.tolist() == [1.0, 2.0, 3.0]


@pytest.mark.parametrize("wavelength_nm, values, reflectance, message", [
    ([500.0], [1.0], False, "is not a spectrum: it needs at least two"),
    ([400.0, 500.0], [1.0, np.nan], False, "NaN or infinite"),
    ([400.0, 400.0, 500.0], [1.0, 1.0, 1.0], False, "lists wavelength 400 nm twice"),
    ([0.38, 0.78], [1.0, 1.0], False, "first column must be the wavelength in nanometres"),
    ([900.0, 1000.0], [1.0, 1.0], False, "misses the visible range"),
    ([400.0, 500.0], [1.0, -0.01], False, "is negative \\(-0.01 at 500 nm\\)"),
    ([400.0, 500.0], [40.0, 87.5], True, "reaches 87.5 at 500 nm \\(2 of 2 values above 1\\): a reflectance lies "
     "within 0-1, and these values look like percent: divide them by 100\\.$"),
    ([400.0, 500.0], [0.5, 1.0001], True, "reaches 1.0001 at 500 nm \\(1 of 2 values above 1\\): .* so this is not "
     "a reflectance: check the file's second column, or clip it to 1\\.$"),
    ([400.0, 500.0], [1.2, 0.5], True, "reaches 1.2 at 400 nm .* so this is not a reflectance"),
    ([400.0, 500.0], [0.5, 250.0], True, "reaches 250 at 500 nm .* so this is not a reflectance"),
    ([400.0, 500.0], [0.0, 0.0], False, "emits nothing within 360-830 nm"),
])
def test_bad_spectra_are_refused_with_the_fix(wavelength_nm, values, reflectance, message):
    with pytest.raises(PrismInputError, match=f"^Spectrum 'x' .*{message}|^Spectrum 'x': .*{message}|{message}") as error:
        check_sampled(wavelength_nm, values, "Spectrum 'x'", reflectance)
    assert str(error.value).startswith("Spectrum 'x'")
