"""Emissive materials: which emit, and their radiance spectrum (strength x spectrum)."""

import numpy as np
import pytest

from engine.tracer import path_spectra as spectra
from engine.tracer.bsdf import emission_spectrum_of, is_emissive
from engine.tracer.spectra.cie import spectral_samples_to_xyz
from engine.tracer.scene import Material, SpectrumSpec
from engine.tracer.spectra.wavelengths import sample_visible_wavelengths


def test_which_materials_emit():
    assert not is_emissive(Material("m"))
    assert is_emissive(Material("m", emission_strength=2.0))
    assert not is_emissive(Material("m", emission=SpectrumSpec(rgb=(0, 0, 0)), emission_strength=2.0))
    assert is_emissive(Material("m", emission=SpectrumSpec(kind="blackbody", temperature_k=3000), emission_strength=1))


def test_emission_spectrum_has_unit_luminance_per_strength():
    mat = Material("m", emission=SpectrumSpec(kind="blackbody", temperature_k=2700), emission_strength=3.0)
    spectrum = emission_spectrum_of(mat, spectra)
    lam, pdf = sample_visible_wavelengths((np.arange(20000) + 0.5) / 20000, 4)
    y = spectral_samples_to_xyz(spectrum(lam), lam, pdf)[:, 1].mean()
    assert y == pytest.approx(1.0, rel=1e-3)
