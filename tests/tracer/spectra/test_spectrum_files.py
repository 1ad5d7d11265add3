"""Spectrum files: CSV (with or without a header) and the measured formats colour-science reads
(IES TM-27-14, Sekonic, UPRTek, using colour-science's own sample files); anything else gets one
message naming the setting and the formats that work."""

from pathlib import Path

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.spectra.cie import import_colour
from engine.tracer.spectra.spectrum_files import read_spectrum_file

WHAT = "Light 'Lamp' ▸ Spectrum File"


def _resources():
    return Path(import_colour().__file__).parent / "io" / "tests" / "resources"


@pytest.mark.parametrize("name, reader, first_nm", [
    ("Fluorescent.spdx", "SpectralDistribution_IESTM2714", 400.0),
    ("RANDOM_001_02._3262K.csv", "SpectralDistribution_Sekonic", 380.0),
    ("uprtek.xls.txt", "SpectralDistribution_UPRTek", 380.0),
])
def test_measured_formats_read_as_colour_science_reads_them(name, reader, first_nm):
    path = _resources() / name
    spectrum = read_spectrum_file(path, WHAT)
    expected = getattr(import_colour(), reader)(str(path)).read()
    assert spectrum.wavelength_nm[0] == first_nm
    assert np.allclose(spectrum.values, expected.values) and np.allclose(spectrum.wavelength_nm, expected.wavelengths)
    assert spectrum.source == str(path)


@pytest.mark.parametrize("text", [
    "wavelength_nm,value\n400,0.1\n500,0.5\n600,0.25\n",
    "400,0.1\n500,0.5\n600,0.25\n",
    "# measured 2024\n400;0.1\n500;0.5\n600;0.25\n",
    "400\t0.1\n500\t0.5\n600\t0.25\n",
    "400 0.1\n500 0.5\n600 0.25\n",
])
def test_csv_with_or_without_header_and_common_delimiters(tmp_path, text):
    path = tmp_path / "lamp.csv"
    path.write_text(text)
    spectrum = read_spectrum_file(path, WHAT, reflectance=True)
    assert spectrum.wavelength_nm == (400.0, 500.0, 600.0) and spectrum.values == (0.1, 0.5, 0.25)


@pytest.mark.parametrize("content, message", [
    (None, "does not exist: choose a spectrum file"),
    (b"\x89PNG\r\n\x1a\n\0\0\0", "is a binary file, not a spectrum"),
    ("400,0.1\n500,0.5\n".encode("utf-16"), "is UTF-16 \\(little-endian\\) text, which Prism does not read: save it "
     "as UTF-8"),
    ("400,0.1\n500,0.5\n".encode("utf-16-be"), "is UTF-16 \\(big-endian\\) text"),
    ("hello world\nthis is not a spectrum\n", "row 2 \\('this is not a spectrum'\\) is not numbers, so this is not a spectrum"),
    ("400,0.1\n500,abc\n", "some rows are not numbers"),
    ("400,0.1,0.2\n500,0.5,0.3\n", "exactly two columns"),
    ("wavelength,a,b\n400,0.1,0.2\n500,0.5,0.3\n", "exactly two columns .* value columns 'a', 'b'"),
    ("0.40,1\n0.50,2\n0.60,3\n", "first column must be the wavelength in nanometres"),
    ("400,1\n500,-2\n", "is negative"),
    ("<?xml version='1.0'?>\n<item></item>\n", "is not a spectrum Prism can read \\(read as an IES TM-27-14"),
])
def test_files_that_are_not_usable_spectra_name_the_setting(tmp_path, content, message):
    path = tmp_path / "lamp.csv"
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif content is not None:
        path.write_text(content)
    with pytest.raises(PrismInputError, match=message) as error:
        read_spectrum_file(path, WHAT)
    assert str(error.value).startswith(f"{WHAT} '{path}'")
