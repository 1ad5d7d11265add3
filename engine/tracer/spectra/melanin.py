"""Spectral absorption of the two melanins that colour hair, per unit concentration as Principled Hair counts it.

Shape: the power laws of Donner & Jensen, "A Spectral BSSRDF for Shading Human Skin" (EGSR 2006, eq. 8-9):
eumelanin σa(λ) ∝ λ^-3.33, pheomelanin σa(λ) ∝ λ^-4.75 (λ in nm; their absolute scales are per mm of skin).
Scale: Cycles 4.5 gives the absorption of a unit concentration as Rec.709 coefficients
(``bsdf_principled_hair_sigma_from_concentration``, ``closure/bsdf_util.h``: eumelanin (0.506, 0.841, 1.653),
pheomelanin (0.343, 0.733, 1.924), per fibre diameter; Blender before 4.0 used (0.419, 0.697, 1.37) and
(0.187, 0.4, 1.05)). Each law is scaled so that its Rec.709 colour (the colour of the spectrum read as a
reflectance under D65, the inverse of Prism's RGB upsampling, ``rgb_to_spectrum``) fits Cycles' coefficients by
least squares weighted with the Rec.709 luminance weights (``tools/fit_melanin.py`` prints the fit). What that
gives (measured, ``tests/tracer/spectra/test_melanin.py``): eumelanin R -8.8 %, G +0.2 %, B +1.7 %; pheomelanin
R -11.5 %, G -0.9 %, B +2.3 % of Cycles' coefficients: the power laws are flatter across red than Cycles' three
numbers, so Prism's red hair absorbs a little less red light than Cycles'.
"""

from __future__ import annotations

from ..jit import kernel

REFERENCE_NM = 550.0
EUMELANIN_EXPONENT = 3.33  # Donner & Jensen 2006
PHEOMELANIN_EXPONENT = 4.75  # Donner & Jensen 2006
EUMELANIN_AT_550 = 0.8222021012753572  # per fibre diameter and unit concentration (fitted, see above)
PHEOMELANIN_AT_550 = 0.7118871173658896

# Cycles 4.5's Rec.709 coefficients the scales are fitted to (``bsdf_util.h``).
CYCLES_EUMELANIN_RGB = (0.506, 0.841, 1.653)
CYCLES_PHEOMELANIN_RGB = (0.343, 0.733, 1.924)


@kernel
def melanin_absorption(eumelanin, pheomelanin, wavelength_nm):
    """Absorption coefficient (per fibre diameter) of the given concentrations at ``wavelength_nm``."""
    x = wavelength_nm / REFERENCE_NM
    return (eumelanin * EUMELANIN_AT_550 * x ** -EUMELANIN_EXPONENT
            + pheomelanin * PHEOMELANIN_AT_550 * x ** -PHEOMELANIN_EXPONENT)
