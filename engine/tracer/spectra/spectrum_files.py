"""Spectra from files: CSV (wavelength in nm, value) and the measured-spectrum formats colour-science
reads — IES TM-27-14 XML (``.spdx``), Sekonic CSV exports and UPRTek text exports.

The format is recognised from the content, not the name. Every file is checked by
``sampled.check_sampled`` (a spectrum, in range, not negative) and becomes a ``SampledSpectrum``;
errors name ``what`` (the object and setting, given by the caller) and the fix.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np

from ..errors import PrismInputError
from ..scene import SampledSpectrum
from ..text_encoding import utf16_advice
from .cie import import_colour
from .sampled import check_sampled

_SEKONIC = re.compile(r"^Spectral Data \d+\[nm\]", re.MULTILINE)
_UPRTEK = re.compile(r"^\d+nm\t", re.MULTILINE)
_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")
_SNIFF_BYTES = 1 << 16


def read_spectrum_file(path, what: str, reflectance: bool = False) -> SampledSpectrum:
    """The checked spectrum in ``path``; ``what`` names the object and setting in messages (e.g.
    ``"Light 'Lamp' ▸ Spectrum File"``); ``reflectance`` also requires values within 0-1."""
    path = Path(path)
    label = f"{what} '{path}'"
    if not path.is_file():
        raise PrismInputError(f"{label} does not exist: choose a spectrum file (CSV, .spdx, Sekonic or UPRTek).")
    try:
        head = path.open("rb").read(_SNIFF_BYTES)
    except OSError as error:
        raise PrismInputError(f"{label} cannot be read ({error.strerror or error}): check its permissions.") from None
    utf16 = utf16_advice(head)
    if utf16:
        raise PrismInputError(f"{label} {utf16}.")
    if b"\0" in head:
        raise PrismInputError(f"{label} is a binary file, not a spectrum: export it as CSV (wavelength_nm, value).")
    text = head.decode("utf-8", errors="replace")
    reader, name = _reader_for(text)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            wavelength_nm, values = reader(path, text)
    except PrismInputError as error:
        raise PrismInputError(f"{label}: {error}") from None
    except Exception as error:  # noqa: BLE001 - a parser's complaint about a malformed file
        detail = " ".join(str(error).split())
        raise PrismInputError(
            f"{label} is not a spectrum Prism can read (read as {name}: {detail}). Prism reads CSV rows of "
            "'wavelength_nm, value' (a header row is optional), IES TM-27-14 XML (.spdx), Sekonic CSV and UPRTek "
            "text exports."
        ) from None
    wavelength_nm, values = check_sampled(wavelength_nm, values, label, reflectance)
    return SampledSpectrum(tuple(wavelength_nm.tolist()), tuple(values.tolist()), str(path))


def _reader_for(text: str):
    stripped = text.lstrip("\ufeff \t\r\n")
    if stripped.startswith("<"):
        return _read_tm2714, "an IES TM-27-14 XML file"
    if _SEKONIC.search(text):
        return _read_sekonic, "a Sekonic export"
    if _UPRTEK.search(text.replace("\r\n", "\n")):
        return _read_uprtek, "a UPRTek export"
    return _read_csv, "a CSV file"


def _values_of(sd):
    return np.asarray(sd.wavelengths, np.float64), np.asarray(sd.values, np.float64)


def _read_tm2714(path, text):
    sd = import_colour().SpectralDistribution_IESTM2714(str(path)).read()
    return _values_of(sd)


def _read_sekonic(path, text):
    return _values_of(import_colour().SpectralDistribution_Sekonic(str(path)).read())


def _read_uprtek(path, text):
    return _values_of(import_colour().SpectralDistribution_UPRTek(str(path)).read())


def _delimiter(line: str):
    for delimiter in (",", ";", "\t"):
        if delimiter in line:
            return delimiter
    return None  # whitespace


def _read_csv(path, text):
    lines = [line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise PrismInputError("the file is empty: it needs rows of 'wavelength_nm, value'.")
    delimiter = _delimiter(lines[0])

    def numbers(line):
        return all(_NUMBER.match(field) for field in (f.strip() for f in line.split(delimiter)) if field)

    if numbers(lines[0]):
        return _headerless(path, delimiter)
    for row, line in enumerate(lines[1:], start=2):
        if not numbers(line):
            raise PrismInputError(
                f"row {row} ('{line.strip()[:40]}') is not numbers, so this is not a spectrum: after an optional "
                "header row every row must be 'wavelength_nm, value'."
            )
    sds = import_colour().io.read_sds_from_csv_file(str(path), delimiter=delimiter or " ")
    if len(sds) != 1:
        names = ", ".join(f"'{name}'" for name in sds) or "none"
        raise PrismInputError(
            f"a spectrum file needs exactly two columns (wavelength_nm, value), this one has value columns {names}: "
            "keep one."
        )
    return _values_of(next(iter(sds.values())))


def _headerless(path, delimiter):
    try:
        table = np.loadtxt(path, delimiter=delimiter, comments="#", ndmin=2, encoding="utf-8")
    except ValueError:
        raise PrismInputError("some rows are not numbers: every row must be 'wavelength_nm, value'.") from None
    if table.shape[1] != 2:
        raise PrismInputError(
            f"a spectrum file needs exactly two columns (wavelength_nm, value), this one has {table.shape[1]}."
        )
    return table[:, 0], table[:, 1]
