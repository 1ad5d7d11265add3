"""Cycles' Clamp Direct / Clamp Indirect on one light contribution (``path_tricks``): a sample's
contribution whose |R| + |G| + |B| (scene-linear Rec.709) exceeds the limit of its class is scaled down
to it. Called only where ``settings.clamping`` is set, so renders without clamps do none of this."""

from __future__ import annotations

from ..jit import kernel
from ..spectra.wavelength_sampling import radiance_to_rgb


@kernel
def clamp_factor(settings, state, i, values, indirect):
    """The factor (≤ 1) that brings path ``i``'s contribution ``values`` [K] (per carried wavelength)
    within Clamp Indirect when ``indirect``, else Clamp Direct."""
    limit = settings.clamp_indirect if indirect else settings.clamp_direct
    r, g, b = radiance_to_rgb(settings.wavelengths, values, state.wavelength[i], state.wavelength_pdf[i])
    total = abs(r) + abs(g) + abs(b)
    return limit / total if total > limit else 1.0
