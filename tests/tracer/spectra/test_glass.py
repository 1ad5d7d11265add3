import math
import warnings

import numpy as np
import pytest

from engine.tracer.spectra import glass as glass_module
from engine.tracer.errors import PrismInputError, UnknownGlassError
from engine.tracer.spectra.glass import (
    catalogue_values,
    constant_ior,
    glass_by_name,
    glass_from_abbe,
    glass_names,
    nearest_catalogue_glass,
)

ALL = glass_names()


def test_catalogue_has_the_twelve_reference_glasses():
    assert len(ALL) == 12
    assert {"N-BK7", "SF11", "N-SF11", "FusedSilica", "S-NPH1", "N-FK51A"} <= set(ALL)


@pytest.mark.parametrize("name", ALL)
def test_catalogue_nd_vd_are_reproduced(name):
    glass = glass_by_name(name)
    nd, vd = catalogue_values(name)
    assert glass.n_d == pytest.approx(nd, abs=1e-5)
    assert glass.v_d == pytest.approx(vd, abs=0.01)
    assert glass.is_dispersive
    wl = np.linspace(max(360.0, glass.valid_range_nm[0]), 830.0, 200)
    n = glass.index(wl)
    assert n.dtype == np.float64 and np.all(n > 1) and np.all(np.diff(n) < 0)


def test_published_index_values():
    # SCHOTT N-BK7 datasheet: n_e (546.07 nm), n_F, n_C, n_g (435.83 nm), n_t (1013.98 nm)
    bk7 = glass_by_name("N-BK7")
    wl = np.array([546.0740, 486.1327, 656.2725, 435.8343, 1013.98])
    assert np.allclose(bk7.index(wl), [1.51872, 1.52238, 1.51432, 1.52668, 1.50731], atol=2e-5)
    # Malitson 1965 fused silica at the HeNe line, 632.8 nm: 1.45702
    assert glass_by_name("FusedSilica").index(632.8) == pytest.approx(1.45702, abs=2e-5)


def test_lookup_is_case_insensitive_and_unknown_names_help():
    assert glass_by_name("n-bk7").name == "N-BK7"
    assert glass_by_name("fused silica").name == "FusedSilica"
    with pytest.raises(UnknownGlassError) as info:
        glass_by_name("BK-7")
    message = str(info.value)
    assert "N-BK7" in message and "FusedSilica" in message and "BK-7" in message
    assert isinstance(info.value, PrismInputError)


def test_glass_from_abbe_reproduces_its_inputs():
    for nd, vd in [(1.5168, 64.17), (1.7847, 25.68), (1.3, 90.0), (2.0, 20.0)]:
        glass = glass_from_abbe(nd, vd)
        assert glass.n_d == pytest.approx(nd, abs=1e-12)
        assert glass.v_d == pytest.approx(vd, rel=1e-12)
        assert glass.is_dispersive
    # close to the real glass across the visible range
    bk7, model = glass_by_name("N-BK7"), glass_from_abbe(1.5168, 64.17)
    wl = np.linspace(400.0, 800.0, 41)
    assert np.abs(bk7.index(wl) - model.index(wl)).max() < 2e-3


@pytest.mark.parametrize("nd, vd", [(1.0, 50.0), (0.9, 50.0), (np.nan, 50.0), (1.5, 0.0), (1.5, -3.0),
                                    (1.5, np.inf), (np.inf, 50.0), (1.5, np.nan), ("glass", 50.0)])
def test_glass_from_abbe_validation(nd, vd):
    with pytest.raises(PrismInputError):
        glass_from_abbe(nd, vd)


def test_extreme_dispersion_is_rejected():
    with pytest.raises(PrismInputError, match="V_d"):
        glass_from_abbe(1.01, 0.2)


def test_constant_ior():
    medium = constant_ior(1.33)
    assert not medium.is_dispersive
    assert np.all(medium.index(np.array([[400.0, 700.0]])) == 1.33)
    assert medium.index(np.zeros((2, 3))).shape == (2, 3)
    assert math.isinf(medium.v_d)
    for bad in (0.0, -1.0, np.nan, np.inf):
        with pytest.raises(PrismInputError):
            constant_ior(bad)


def test_nearest_catalogue_glass():
    assert nearest_catalogue_glass(1.517).name == "N-BK7"
    assert nearest_catalogue_glass(1.785, 25.7).name in ("N-SF11", "SF11")
    assert nearest_catalogue_glass(1.46).name == "FusedSilica"
    with pytest.raises(PrismInputError):
        nearest_catalogue_glass(np.nan)


def test_below_valid_range_clamps_warns_once_and_counts(monkeypatch):
    monkeypatch.setattr(glass_module, "_WARNED", set())
    sf11 = glass_by_name("SF11")  # valid from 390 nm
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        n = sf11.index(np.array([360.0, 380.0, 390.0, 500.0]))
        sf11.index(np.array([370.0]))
        glass_by_name("SF11").index(365.0)  # another instance of the same glass: still silent
    assert n[0] == n[1] == n[2] == sf11.index(390.0)
    assert np.isfinite(n).all()
    messages = [str(w.message) for w in caught]
    assert len(messages) == 1 and "SF11" in messages[0] and "390" in messages[0]
    assert sf11.out_of_range_count == 3
    assert glass_by_name("N-BK7").out_of_range_count == 0


def test_dispersion_validation_rejects_a_pole_in_the_visible():
    from engine.tracer.spectra.glass import SellmeierGlass, _validate_dispersion

    bad = SellmeierGlass("Broken", [1.0, 0.0, 0.0], [0.25, 0.01, 100.0], (300.0, 2500.0))  # pole at 500 nm
    with pytest.raises(PrismInputError, match="Broken"):
        _validate_dispersion(bad, "Catalogue glass 'Broken'")
