"""Surface emission (Cycles' Emission closure): radiance = strength x spectrum, the
same on both sides of the surface, independent of direction. The spectrum is the
material's ``emission`` SpectrumSpec (RGB white when None), luminance-normalised."""

from __future__ import annotations

from ..scene import SpectrumSpec


def emission_spectrum_of(material, spectra):
    """Callable wavelength_nm [n,K] -> radiance per unit strength [n,K] of an emissive material."""
    return spectra.emission(material.emission or SpectrumSpec())


def is_emissive(material) -> bool:
    """True if the material emits light (strength > 0 and a non-black spectrum)."""
    if not material.emission_strength > 0:
        return False
    spec = material.emission
    return spec is None or spec.kind != "rgb" or max(spec.rgb) > 0
