"""Blender's Wavelength node: the colour Cycles gives its Wavelength input (in nm).

Cycles (``svm_node_wavelength``) interpolates the CIE 1931 2° colour-matching functions linearly between
5 nm knots from 380 to 780 nm, converts XYZ (D65) to the scene-linear space, scales by 1/2.52 so that no
channel exceeds 1, and clamps negative channels to 0; outside the knots the colour is black. Prism takes
the CIE functions from colour-science (``tracer.spectra.cie``) and the same matrix its film uses. A
constant wavelength becomes a constant colour; a varying one reads the knots as a colour-ramp table.
"""

from __future__ import annotations

import numpy as np

from ...tracer.materials import opcodes as op
from .terms import COLOR, FLOAT

FIRST_KNOT_NM = 380.0
KNOT_SPACING_NM = 5.0
KNOTS = 81  # 380, 385, ..., 780 nm
CYCLES_SCALE = 1.0 / 2.52  # Cycles' empirical factor keeping every channel of every wavelength <= 1


def knot_colours() -> np.ndarray:
    """Scene-linear Rec.709 [KNOTS, 3] of the knots before clamping (negative outside the gamut)."""
    from ...tracer.spectra import cie

    nm = FIRST_KNOT_NM + KNOT_SPACING_NM * np.arange(KNOTS)
    return cie.xyz_to_linear_rec709(cie.cie_xyz_cmf(nm)) * CYCLES_SCALE


def wavelength_rgb(wavelength_nm: float) -> tuple[float, float, float]:
    """The node's colour at ``wavelength_nm``, computed as Cycles computes it (its index truncated toward
    zero, so 375-380 nm extrapolate the first interval, and 780 nm and above are black)."""
    position = (wavelength_nm - FIRST_KNOT_NM) / KNOT_SPACING_NM
    if not np.isfinite(position):
        return 0.0, 0.0, 0.0
    i = int(position)
    if i < 0 or i >= KNOTS - 1:
        return 0.0, 0.0, 0.0
    knots = knot_colours()
    t = position - i
    rgb = np.maximum((1.0 - t) * knots[i] + t * knots[i + 1], 0.0)
    return tuple(float(x) for x in rgb)


def wavelength_node(c, node, context, variant, identifier):
    wavelength = c.value(node, "Wavelength", context, FLOAT, variant)
    known = c.known(wavelength)
    if c.evaluate is None:  # a preview (the material panel): no colour science at draw time
        return {"Color": (c.const(1.0, 1.0, 1.0), COLOR)}
    if known is not None:
        return {"Color": (c.const(*wavelength_rgb(known)), COLOR)}
    rows = np.concatenate([knot_colours(), np.ones((KNOTS, 1))], axis=1)
    table = c.const(*rows.reshape(-1).tolist())
    span = KNOT_SPACING_NM * (KNOTS - 1)
    position = c.math("DIVIDE", c.math("SUBTRACT", wavelength, c.const(FIRST_KNOT_NM)), c.const(span))
    ramp = c.emit(op.COLOR_RAMP, [position, table, KNOTS], mode=0, width=4, reads=[table])
    colour = c.vector_math("MAXIMUM", ramp.__class__(ramp.register, 3), c.const(0.0, 0.0, 0.0))
    # Black outside the knots (the ramp would hold its end colours); 375-380 nm, which Cycles extrapolates,
    # reads the 380 nm colour here.
    inside = c.math("MULTIPLY", c.math("GREATER_THAN", wavelength, c.const(FIRST_KNOT_NM - KNOT_SPACING_NM)),
                    c.math("LESS_THAN", wavelength, c.const(FIRST_KNOT_NM + span)))
    return {"Color": (c.vector_math("SCALE", colour, s=inside), COLOR)}


HANDLERS = {"ShaderNodeWavelength": wavelength_node}
