"""The melanin absorption spectra (``spectra.melanin``): Donner & Jensen's power laws, scaled so that their Rec.709
colour reproduces Cycles 4.5's coefficients as closely as the stated (measured) errors."""

import numpy as np
import pytest

from engine.tracer.spectra import melanin
from tools.fit_melanin import fit


@pytest.mark.parametrize("exponent, scale, rgb, errors", [
    (melanin.EUMELANIN_EXPONENT, melanin.EUMELANIN_AT_550, melanin.CYCLES_EUMELANIN_RGB, (-0.0881, 0.0020, 0.0168)),
    (melanin.PHEOMELANIN_EXPONENT, melanin.PHEOMELANIN_AT_550, melanin.CYCLES_PHEOMELANIN_RGB,
     (-0.1149, -0.0095, 0.0225)),
])
def test_the_spectra_give_cycles_coefficients_in_rec709(exponent, scale, rgb, errors):
    fitted, error = fit(exponent, rgb)
    assert scale == pytest.approx(fitted, rel=1e-9)
    np.testing.assert_allclose(error, errors, atol=2e-4)
    assert abs(error[1]) < 0.01  # green, most of the luminance, within 1 %


def test_the_kernel_evaluates_the_power_laws():
    nm = np.array([450.0, 550.0, 650.0])
    got = np.array([melanin.melanin_absorption(0.5, 0.25, x) for x in nm])
    expected = (0.5 * melanin.EUMELANIN_AT_550 * (nm / 550) ** -3.33
                + 0.25 * melanin.PHEOMELANIN_AT_550 * (nm / 550) ** -4.75)
    np.testing.assert_allclose(got, expected, rtol=1e-12)
    assert got[0] > got[1] > got[2]  # melanin absorbs blue most: hair is brown to red
