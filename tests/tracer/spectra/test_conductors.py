import numpy as np
import pytest

from engine.tracer.spectra.conductors import conductor_names, conductor_nk, conductor_range_nm
from engine.tracer.errors import PrismInputError
from helpers.fresnel import fresnel_conductor
from helpers.spectral_oracles import reflectance_spectrum_to_rgb


def test_names():
    assert conductor_names() == ["Au", "Ag", "Cu", "Al"]


def test_published_table_values():
    # Johnson & Christy 1972 at 2.26 eV (548.6 nm)
    n, k = conductor_nk("Au", 548.6)
    assert (n, k) == pytest.approx((0.43, 2.455))
    assert conductor_nk("Ag", 548.6) == pytest.approx((0.06, 3.586))
    assert conductor_nk("Cu", 548.6) == pytest.approx((1.02, 2.577))
    # Rakic et al. 1998 model for Al near 550 nm: n ~ 0.97, k ~ 6.4
    n, k = conductor_nk("Al", 550.0)
    assert n == pytest.approx(0.965, abs=0.01) and k == pytest.approx(6.40, abs=0.05)


def test_tables_cover_the_visible_range_and_interpolate():
    for name in conductor_names():
        lo, hi = conductor_range_nm(name)
        assert lo <= 360.0 and hi >= 830.0
        wl = np.linspace(360.0, 830.0, 95).reshape(5, 19)
        n, k = conductor_nk(name, wl)
        assert n.shape == k.shape == wl.shape
        assert np.all(n > 0) and np.all(k > 0)
    n_mid, _ = conductor_nk("Au", 0.5 * (548.6 + 582.1))
    assert n_mid == pytest.approx(0.5 * (0.43 + 0.29))


def test_metal_colours_make_sense():
    wl = np.array([450.0, 650.0])
    gold = fresnel_conductor(1.0, *conductor_nk("Au", wl))
    copper = fresnel_conductor(1.0, *conductor_nk("Cu", wl))
    silver = fresnel_conductor(1.0, *conductor_nk("Ag", wl))
    assert gold[1] > gold[0] + 0.3 and copper[1] > copper[0] + 0.3  # yellow / red metals
    assert silver.min() > 0.9
    assert 0.85 < fresnel_conductor(1.0, *conductor_nk("Al", 550.0)) < 0.95


def test_unknown_conductor_and_bad_wavelengths():
    assert conductor_nk("au", 500.0) == conductor_nk("Au", 500.0)
    with pytest.raises(PrismInputError, match="Au, Ag, Cu, Al"):
        conductor_nk("Pt", 500.0)
    with pytest.raises(PrismInputError):
        conductor_nk("Au", np.nan)


def test_normal_incidence_colours_are_the_familiar_metal_colours():
    """Linear Rec.709 F0 under D65 vs commonly quoted values (Real-Time Rendering 4th ed., Table 9.2).

    Those come from other measurements, so only a loose match is expected.
    """
    quoted = {"Au": (1.000, 0.782, 0.344), "Ag": (0.972, 0.960, 0.915), "Cu": (0.955, 0.638, 0.538),
              "Al": (0.913, 0.922, 0.924)}
    for name, expected in quoted.items():
        rgb = reflectance_spectrum_to_rgb(lambda wl, name=name: fresnel_conductor(1.0, *conductor_nk(name, wl)))
        assert np.allclose(rgb, expected, atol=0.07), (name, rgb)
