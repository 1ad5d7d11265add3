"""``MediumSpec``: a homogeneous medium as the export layer hands it to the tracer (Blender's settings).

Cycles' volume closures, per unit length (metres): Volume Scatter adds scattering σ_s = density × colour,
Volume Absorption adds absorption σ_a = density × (1 - colour), Principled Volume adds σ_s = density ×
colour and σ_a = density × max(1 - colour, 0) × max(1 - sqrt(absorption colour), 0); emission (Principled's
Emission Strength × Emission Color) is radiance added per metre travelled, not scaled by density. Prism
upsamples each colour to a reflectance spectrum (``spectra.rgb_to_spectrum``), so σ_s, σ_a and the
emission are functions of wavelength.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class MediumSpec:
    """``scatter``: (density, rgb) terms, σ_s(λ) = Σ density × R_rgb(λ); ``absorb``: (density, rgb, ...)
    terms, σ_a(λ) = Σ density × Π (1 - R_rgb(λ)) over the term's colours; ``anisotropy``: the
    Henyey-Greenstein g of the scattering (-1..1); ``emission``: (strength, rgb) terms of emitted radiance
    per metre."""

    name: str
    scatter: list = field(default_factory=list)
    absorb: list = field(default_factory=list)
    anisotropy: float = 0.0
    emission: list = field(default_factory=list)
