"""The illuminant library: every spectrum of colour-science's SDS_ILLUMINANTS renders luminance-
normalised at its colour-science chromaticity, and a colour-checker patch is its measured curve."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.scene import ReflectanceSpec, SpectrumSpec
from engine.tracer.spectra import cie
from engine.tracer.spectra.illuminants import canonical_illuminant, illuminant_names
from engine.tracer.spectra.measured_reflectance import reflectance_names
from engine.tracer.spectra.table import SpectrumTable, spectrum_values
from engine.tracer.spectra.trapezoid import trapezoid

GRID = np.arange(360.0, 830.5, 0.25)


def _xyz_of_row(table, sid):
    values = np.empty(len(GRID))
    spectrum_values(table.arrays(), sid, GRID, values)
    return trapezoid(values[:, None] * cie.cie_xyz_cmf(GRID), GRID, axis=0) / cie.CMF_Y_INTEGRAL


def test_every_illuminant_is_luminance_normalised_at_its_chromaticity():
    colour = cie.import_colour()
    names = illuminant_names()
    assert {"A", "D65", "FL2", "FL3.15", "HP1", "HP5", "LED-B3", "LED-V2", "ISO 7589 Photoflood"} <= set(names)
    table = SpectrumTable()
    rows = {name: table.emission(SpectrumSpec(kind="illuminant", illuminant=name)) for name in names}
    for name, sid in rows.items():
        xyz = _xyz_of_row(table, sid)
        reference = colour.sd_to_XYZ(colour.SDS_ILLUMINANTS[name], method="Integration")
        assert xyz[1] == pytest.approx(1.0, abs=2e-3), name
        assert np.abs(xyz[:2] / xyz.sum() - reference[:2] / reference.sum()).max() < 1e-3, name


def test_illuminant_keys_ignore_case_and_unknown_keys_suggest_the_nearest():
    assert canonical_illuminant(" fl2 ") == "FL2" and canonical_illuminant("led-b3") == "LED-B3"
    with pytest.raises(PrismInputError, match="'FL13' is not one of colour-science's standard illuminants; "
                                              "did you mean 'FL3', 'FL1'"):
        canonical_illuminant("FL13", "Light 'Lamp'")


def test_colour_checker_patches_are_their_measured_reflectance():
    colour = cie.import_colour()
    names = reflectance_names()
    assert "ColorChecker N Ohta: dark skin" in names and "BabelColor Average: white 9.5 (.05 D)" in names
    assert not any(name.startswith(("cc_ohta", "babel_average")) for name in names)  # aliases left out
    table = SpectrumTable()
    sid = table.measured_reflectance(ReflectanceSpec(kind="measured", name="BabelColor Average: moderate red"))
    values = np.empty(len(GRID))
    spectrum_values(table.arrays(), sid, GRID, values)
    sd = colour.SDS_COLOURCHECKERS["BabelColor Average"]["moderate red"]
    inside = (GRID >= 380) & (GRID <= 730)
    assert np.allclose(values[inside], np.interp(GRID[inside], sd.wavelengths, sd.values), atol=1e-12)
    assert np.all(values[GRID > 730] == sd.values[-1])  # the end values continue
