"""Emissive materials: which emit, and their radiance spectrum in the material table (strength x spectrum)."""

import numpy as np
import pytest

from engine.tracer.materials.table import MAT_EMISSIVE, build_materials, is_emissive
from engine.tracer.scene import Material, SpectrumSpec
from engine.tracer.spectra.cie import spectral_samples_to_xyz
from engine.tracer.spectra.table import SpectrumTable, spectrum_values
from engine.tracer.spectra.wavelengths import sample_visible_wavelengths


def test_which_materials_emit():
    assert not is_emissive(Material("m"))
    assert is_emissive(Material("m", emission_strength=2.0))
    assert not is_emissive(Material("m", emission=SpectrumSpec(rgb=(0, 0, 0)), emission_strength=2.0))
    assert is_emissive(Material("m", emission=SpectrumSpec(kind="blackbody", temperature_k=3000), emission_strength=1))


def test_emission_spectrum_has_unit_luminance_per_strength():
    mat = Material("m", emission=SpectrumSpec(kind="blackbody", temperature_k=2700), emission_strength=3.0)
    spectra = SpectrumTable()
    table = build_materials([mat, Material("plain")], {0, 1}, spectra)
    arrays = table.arrays
    assert arrays.flags[0] & MAT_EMISSIVE and not arrays.flags[1] & MAT_EMISSIVE
    assert arrays.emission_strength.tolist() == [3.0, 0.0]
    lam, pdf = sample_visible_wavelengths((np.arange(20000) + 0.5) / 20000, 4)
    values = np.empty(lam.shape)
    for row, out in zip(lam, values):
        spectrum_values(spectra.arrays(), int(arrays.emission_spectrum[0]), row, out)
    y = spectral_samples_to_xyz(values, lam, pdf)[:, 1].mean()
    assert y == pytest.approx(1.0, rel=1e-3)
