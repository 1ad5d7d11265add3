"""A lens system as kernel tables: geometry per surface and one glass row per medium."""

import math

import numpy as np
import pytest

from engine.tracer.lens.lens_file import load_lens
from engine.tracer.lens.media import AIR, FunctionMedium, catalogue_medium, constant_medium
from engine.tracer.lens.tables import lens_tables, medium_row
from engine.tracer.spectra.dispersion import refractive_index

from .lens_cameras import lens_path

WAVELENGTHS_NM = (404.66, 587.56, 706.52)


def test_double_gauss_tables_follow_the_prescription():
    system = load_lens(lens_path("double_gauss_50mm"))
    tables = lens_tables(system)
    count = len(system.surfaces)
    assert tables.medium_rows.shape[0] == count + 1
    np.testing.assert_array_equal(tables.vertex_z_mm, system.vertex_z_mm)
    np.testing.assert_array_equal(tables.is_stop, [s.is_stop for s in system.surfaces])
    np.testing.assert_array_equal(tables.semi_aperture_mm, [s.aperture_mm / 2 for s in system.surfaces])
    for i, surface in enumerate(system.surfaces):
        expected = 0.0 if surface.is_stop or math.isinf(surface.radius_mm) else 1.0 / surface.radius_mm
        assert tables.curvature_per_mm[i] == expected
        for wavelength in (486.13, 656.27):  # medium after surface i, as the numpy glass gives it
            n = refractive_index(tables.medium_rows[i + 1], wavelength)[0]
            assert n == pytest.approx(float(surface.medium.index(np.array([wavelength]))[0]), rel=1e-14)
    assert refractive_index(tables.medium_rows[0], 550.0)[0] == 1.0
    assert refractive_index(tables.medium_rows[-1], 550.0)[0] == 1.0


@pytest.mark.parametrize("medium", [
    AIR, constant_medium(1.7), catalogue_medium("N-SF11"),
    FunctionMedium(lambda wl: 1.5046 + 4200.0 / wl**2, "cauchy"),
], ids=["air", "constant", "sellmeier", "cauchy-function"])
def test_rows_give_the_media_indices(medium):
    row = medium_row(medium)
    for wavelength in WAVELENGTHS_NM:
        expected = float(medium.index(np.array([wavelength]))[0])
        assert refractive_index(row, wavelength)[0] == pytest.approx(expected, rel=1e-13)


def test_a_function_medium_is_never_clamped():
    row = medium_row(FunctionMedium(lambda wl: 1.6 + 9000.0 / wl**2))
    for wavelength in (250.0, 2000.0):
        n, clamped = refractive_index(row, wavelength)
        assert n == pytest.approx(1.6 + 9000.0 / wavelength**2, rel=1e-13) and not clamped


def test_a_function_without_a_kernel_form_is_refused():
    with pytest.raises(TypeError, match="'wavy' has no kernel form"):
        medium_row(FunctionMedium(lambda wl: 1.5 + 0.01 * np.sin(wl / 40.0), "wavy"))
